//! Friction of smooth lateral walls on the fluid of a narrow channel.

use crate::param::Describe;

/// Darcy-Weisbach friction of a smooth wall: the wall shear stress at mean velocity U is
/// tau_w = rho_f f(Re) U^2 / 8 with Re = |U| W / nu_f built on the channel width W
/// (Maurin et al. 2015 section III B, the Einstein side-wall method). A model gives the
/// Poiseuille number f Re, which stays finite where the flow stops (the laminar law
/// f = C / Re has f Re = C), so that the stress tau_w = rho_f nu_f (f Re) U / (8 W) is
/// evaluated without a 0 / 0 at rest.
#[typetag::serde(tag = "type")]
pub trait WallFriction: Describe + Send + Sync + std::fmt::Debug {
    /// Poiseuille number f Re at Re = |U| W / nu_f >= 0.
    fn poiseuille_number(&self, re: f64) -> f64;

    /// Friction factor f at Re > 0 (infinite at Re = 0 for a laminar law).
    fn friction_factor(&self, re: f64) -> f64 {
        self.poiseuille_number(re) / re
    }

    /// The Poiseuille number in place of each Reynolds number of `re`.
    fn poiseuille_batch(&self, re: &mut [f64]) {
        for r in re.iter_mut() {
            *r = self.poiseuille_number(*r);
        }
    }
}
