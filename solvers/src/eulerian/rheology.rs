//! The particle-phase stress of the Eulerian solver: pressure p_p(phi, ...) with its
//! derivative for the implicit volume-fraction step, and the shear stress at a face with
//! its tangent for the implicit momentum step, for either kind of granular closure.

use saltus_core::{KineticTheory, LocalRheology, LocalState};

/// Johnson & Jackson elastic pressure (Chassagne 2023 eq 2.14) given to local
/// rheologies, whose closures carry no enduring-contact pressure: without it a static bed
/// (gamma_dot = 0) has no pressure at any phi below jamming.
pub type Elastic = saltus_core::JohnsonJacksonElastic;

/// Which granular closure the run uses.
#[derive(Clone, Copy)]
pub enum Rheology<'a> {
    /// Johnson-Jackson elastic + kinetic theory: granular temperature equation on.
    Kinetic {
        /// the closure
        model: &'a dyn KineticTheory,
        /// its enduring-contact pressure, evaluated inline
        elastic: Elastic,
    },
    /// mu(I), mu(K): dilatancy pressure from the packing law, plus an elastic pressure.
    Local {
        /// the closure
        model: &'a dyn LocalRheology,
        /// its enduring-contact pressure
        elastic: Elastic,
    },
}

/// Pressure at one cell, linearised in phi: p(phi') ~ a phi' + b near the current phi.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pressure {
    /// p_p (Pa)
    pub p: f64,
    /// of which enduring-contact (elastic) part (Pa)
    pub p_el: f64,
    /// dp/dphi used by the implicit phi step (Pa), >= 0
    pub a: f64,
    /// p - a phi (Pa)
    pub b: f64,
}

impl Rheology<'_> {
    /// Volume fraction at which the particle pressure diverges.
    pub fn phi_max(&self) -> f64 {
        match self {
            Rheology::Kinetic { model, .. } => model.phi_max(),
            Rheology::Local { elastic, .. } => elastic.phi_max,
        }
    }

    /// Pressure of a local rheology at `phi` and shear rate `gamma`: elastic plus
    /// dilatancy p such that packing(control(p, gamma)) = phi.
    pub fn local_pressure(model: &dyn LocalRheology, elastic: &Elastic, state: &LocalState, phi: f64) -> f64 {
        let x = model.control_of_packing(phi);
        let shear = if x > 0.0 { model.pressure_at(state, x) } else { 0.0 };
        elastic.pressure(phi) + if shear.is_finite() { shear } else { 0.0 }
    }
}

/// Coulomb-type stress tau = mu p g / sqrt(g^2 + r^2) with its secant viscosity tau / g
/// (the regularisation makes a static bed a very viscous fluid). The momentum step uses the
/// secant, not the tangent: a tangent linearisation leaves the yield stress explicit, and an
/// explicit rate-independent stress chatters in sign at any practical time step.
#[inline]
pub fn coulomb(mu_p: f64, g: f64, r: f64) -> (f64, f64) {
    let s = (g * g + r * r).sqrt();
    (mu_p * g / s, mu_p / s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elastic_derivative_matches_difference() {
        let e = Elastic { p0: 0.05, phi_rlp: 0.57, phi_max: 0.635 };
        for phi in [0.58, 0.6, 0.62, 0.63] {
            let h = 1e-8;
            let fd = (e.pressure(phi + h) - e.pressure(phi - h)) / (2.0 * h);
            assert!((e.derivative(phi) - fd).abs() <= 1e-5 * fd, "{phi}: {} vs {fd}", e.derivative(phi));
        }
        assert_eq!(e.pressure(0.5), 0.0);
        assert_eq!(e.pressure(0.635), f64::INFINITY);
    }

    #[test]
    fn coulomb_limits() {
        let (t, d) = coulomb(2.0, 1e3, 1e-4);
        assert!((t - 2.0).abs() < 1e-12 && (d - 2e-3).abs() < 1e-12);
        let (t, d) = coulomb(2.0, 0.0, 1e-4);
        assert_eq!(t, 0.0);
        assert!((d - 2.0 / 1e-4).abs() < 1e-6);
    }
}
