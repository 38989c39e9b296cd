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
//! # Friction factor of the smooth walls
//!
//! Turbulent: the smooth-wall resistance law of Graf & Altinakar (1998),
//! 1/sqrt(f) = 2 log10(Re sqrt(f) / 4) + 0.32 (Prandtl-Karman form), solved exactly for
//! f (Newton on ln(1/sqrt f), where the law is convex and monotone). The Reynolds number
//! is built on the width, Re = |u| W / nu_f, as in the implementation of the paper's
//! authors (Yade's `HydroForceEngine`, `fluidWallFriction`, `wallFrictionModel = 1`),
//! which writes the law in this form; we could not read the textbook itself. Over the
//! range of the Frey flume (u = 0.4-1 m/s in a 6.5 mm channel, Re = 2600-6500) it gives
//! f = 0.036-0.047, within 7 % of Blasius' smooth-wall law 0.3164 Re^-1/4 (test
//! `friction_factor_agrees_with_blasius_in_its_range`, 3e3 <= Re <= 1e5).
//!
//! Laminar: below Re = [`RE_LAMINAR`], f = 48 / Re, the exact plane-Poiseuille wall
//! stress 6 mu U / W between two plates a distance W apart (in Darcy form with the
//! hydraulic diameter 2W, f = 96 / Re_Dh). The switch is where the two laws cross, so f
//! is continuous; the transitional regime is not modelled. In the laminar range
//! gamma_w = 12 eps mu_f / W^2 does not depend on u: the column's equation is then the
//! Brinkman (Hele-Shaw) equation of a slot, with a closed-form solution
//! (test `laminar_slot_matches_the_brinkman_profile`).
//!
//! Valid range: smooth walls (glass, perspex) of a channel of width W a few grains wide or
//! less, where the flow between the walls is the same at every y (quasi-2D). Wider
//! channels make the term small (gamma_w ~ 1/W): W -> infinity recovers the column
//! without walls.

use serde::{Deserialize, Serialize};

/// Reynolds number |u| W / nu_f below which the wall friction factor is the laminar
/// 48 / Re: where 48 / Re equals the Graf-Altinakar law (to 1e-9, test
/// `friction_factor_is_continuous_at_the_switch`).
pub const RE_LAMINAR: f64 = 617.970_325_458_568;

/// Two smooth lateral walls a distance `width` apart (Maurin et al. 2015 section III B).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideWalls {
    /// channel width W between the walls (m)
    pub width: f64,
}

/// Darcy-Weisbach friction factor of a smooth wall at Re = |u| W / nu_f: 48 / Re up to
/// [`RE_LAMINAR`], else the root of 1/sqrt(f) = 2 log10(Re sqrt(f) / 4) + 0.32
/// (Graf & Altinakar 1998). Infinite at Re = 0 (the laminar wall stress stays finite:
/// see [`SideWalls::coefficients`]).
pub fn friction_factor(re: f64) -> f64 {
    if re <= RE_LAMINAR {
        return 48.0 / re;
    }
    // with y = ln(1/sqrt f): e^y + a y = c, a = 2 / ln 10, c = a ln(Re / 4) + 0.32,
    // convex and increasing in y: Newton converges from any start (monotonically after
    // the first step)
    let a = 2.0 / std::f64::consts::LN_10;
    let c = a * (0.25 * re).ln() + 0.32;
    let mut y = c.max(1.0).ln();
    for _ in 0..60 {
        let e = y.exp();
        let step = (e + a * y - c) / (e + a);
        y -= step;
        if step.abs() <= 1e-15 * y.abs().max(1.0) {
            break;
        }
    }
    (-2.0 * y).exp()
}

impl SideWalls {
    /// gamma_w per cell (kg m^-3 s^-1) into `out`: the walls remove gamma_w u per unit
    /// volume, gamma_w = (1 - phi) rho_f f(Re) |u| / (4 W), Re = |u| W / nu_f; in the
    /// laminar range 12 (1 - phi) rho_f nu_f / W^2 (the same value, written without the
    /// 0 / 0 at rest).
    pub fn coefficients(&self, density: f64, viscosity: f64, phi: &[f64], u: &[f64], out: &mut [f64]) {
        let w = self.width;
        let laminar = 12.0 * density * viscosity / (w * w);
        for ((g, &p), &ui) in out.iter_mut().zip(phi).zip(u) {
            let speed = ui.abs();
            let re = speed * w / viscosity;
            let per_eps = if re <= RE_LAMINAR { laminar } else { density * friction_factor(re) * speed / (4.0 * w) };
            *g = (1.0 - p) * per_eps;
        }
    }
}
