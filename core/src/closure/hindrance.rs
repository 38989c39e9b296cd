//! Hindrance (crowding) correction of the drag force.

use crate::param::Describe;

/// Factor multiplying the single-particle drag force at the same relative velocity, so
/// that the drag on a particle in a suspension of volume fraction `phi` is
/// F = f(phi, Re_p) (1/2) rho_f (pi d^2/4) C_D(Re*) |u_r| u_r, where
/// Re_p = |u_f - v_p| d / nu_f is the *interstitial* particle Reynolds number and
/// Re* = [`Hindrance::drag_reynolds`] is the one at which C_D is evaluated.
#[typetag::serde(tag = "type")]
pub trait Hindrance: Describe + Send + Sync + std::fmt::Debug {
    /// Hindrance factor at volume fraction `phi` in [0, 1) and interstitial Re_p >= 0.
    fn factor(&self, phi: f64, re_p: f64) -> f64;

    /// Reynolds number at which the single-particle C_D is evaluated (the model's
    /// convention): interstitial by default.
    fn drag_reynolds(&self, _phi: f64, re_p: f64) -> f64 {
        re_p
    }

    /// Factor over slices of equal length.
    fn factor_batch(&self, phi: &[f64], re_p: &[f64], out: &mut [f64]) {
        for ((o, &p), &r) in out.iter_mut().zip(phi).zip(re_p) {
            *o = self.factor(p, r);
        }
    }
}
