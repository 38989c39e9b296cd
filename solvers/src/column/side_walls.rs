//! Friction of two smooth lateral walls on the fluid of a quasi-2D channel: the
//! correction of Maurin et al. 2015 section III B, a sink term in the column momentum
//! (their eq 19) "evaluated from the classical Einstein method with a Graf and Altinakar
//! friction factor" (their refs 50, 51: Graf & Altinakar 1998, Frey et al. 2006).
//!
//! # Method
//!
//! The paper names the method without writing it; what follows is Einstein's side-wall
//! method (H. A. Einstein 1942; Vanoni & Brooks 1957; Graf & Altinakar 1998) taken per
//! height of the column, as the paper puts it in eq 19. Einstein splits the channel's
//! cross-section between the bed and the two walls, each carrying the shear stress of its
//! own friction factor at the common velocity: a smooth wall carries
//! tau_w = rho_f f_w U^2 / 8 (Darcy-Weisbach). In the 1D column the velocity is u(z), so
//! each wall carries tau_w(z) = rho_f f_w(z) u(z)^2 / 8 over its wetted fraction eps(z) =
//! 1 - phi(z) of the wall, and the two walls of a channel of width W remove, per unit
//! volume of the column,
//!
//! ```text
//! S_w(z) = (2 / W) eps tau_w = eps rho_f f_w |u| u / (4 W) = gamma_w(z) u(z),
//! gamma_w = eps rho_f f_w(Re) |u| / (4 W)   (kg m^-3 s^-1),   Re = |u| W / nu_f.
//! ```
//!
//! The column treats gamma_w u as it treats the drag beta (u - u_p) with u_p = 0: gamma_w
//! lagged (from the velocity at the start of the step, or the current iterate of the
//! steady solve), u implicit.
//!
//! # Friction factor of the walls
//!
//! The friction factor is a closure of the family `wall_friction` (`[closures.wall_friction]`,
//! e.g. `graf_altinakar`), which gives the Poiseuille number f Re: the walls' coefficient is
//! then gamma_w = eps rho_f nu_f (f Re) / (4 W^2), finite at rest. With the laminar law
//! f Re = 48, gamma_w = 12 eps mu_f / W^2 does not depend on u and the column's equation is
//! the Brinkman (Hele-Shaw) equation of a slot, with a closed-form solution (test
//! `laminar_slot_matches_the_brinkman_profile`).
//!
//! Valid range: smooth walls (glass, perspex) of a channel of width W a few grains wide or
//! less, where the flow between the walls is the same at every y (quasi-2D). Wider
//! channels make the term small (gamma_w ~ 1/W): W -> infinity recovers the column
//! without walls.

use saltus_core::WallFriction;
use serde::{Deserialize, Serialize};

/// Two smooth lateral walls a distance `width` apart (Maurin et al. 2015 section III B).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideWalls {
    /// channel width W between the walls (m)
    pub width: f64,
}

impl SideWalls {
    /// gamma_w per cell (kg m^-3 s^-1) into `out`: the walls remove gamma_w u per unit
    /// volume, gamma_w = (1 - phi) rho_f nu_f (f Re) / (4 W^2) with the Poiseuille number
    /// f Re of `friction` at Re = |u| W / nu_f (= (1 - phi) rho_f f |u| / (4 W), written
    /// without the 0 / 0 at rest).
    pub fn coefficients(
        &self,
        friction: &dyn WallFriction,
        density: f64,
        viscosity: f64,
        phi: &[f64],
        u: &[f64],
        out: &mut [f64],
    ) {
        let w = self.width;
        for (o, &ui) in out.iter_mut().zip(u) {
            *o = ui.abs() * w / viscosity;
        }
        friction.poiseuille_batch(out);
        let scale = density * viscosity / (4.0 * w * w);
        for (g, &p) in out.iter_mut().zip(phi) {
            *g *= (1.0 - p) * scale;
        }
    }
}
