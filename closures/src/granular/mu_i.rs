//! mu(I) local rheology.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, GranularStress, Limit, LocalRheology, LocalState};
use serde::{Deserialize, Serialize};

/// mu(I) rheology of dense granular flows, bedload constants of Maurin et al. (2016)
///
/// ```text
/// I      = d |gamma_dot| / sqrt(p / rho_p)
/// mu(I)  = mu_s + (mu_2 - mu_s) / (I0/I + 1)
/// phi(I) = phi_c / (1 + b I)
/// ```
///
/// * Source: Chassagne et al. 2023 eqs 1.1-1.2 (GDR MiDi 2004; Maurin, Chauchat & Frey
///   2016, J. Fluid Mech. 804, R1).
/// * Defaults: `mu_s = 0.35`, `mu_2 = 0.97`, `i0 = 0.69`, `phi_c = 0.61`, `b = 0.31`.
/// * Valid range: `mu_s` in [0, 2], `mu_2` in [0, 5] with `mu_2 > mu_s`, `i0 > 0`,
///   `phi_c` in (0, 1), `b >= 0`; I >= 0. mu rises monotonically from mu_s (I = 0) to
///   mu_2 (I -> inf); phi falls from phi_c to 0.
/// * Decisions: I = 0 when |gamma_dot| = 0 (whatever p); I = +inf when p <= 0 and
///   |gamma_dot| > 0 (no confinement: the free-flight limit, mu = mu_2, phi = 0). Both
///   `friction` and `packing` accept +inf and return those limits; never NaN for I >= 0.
/// * Declared limits: mu -> `mu_s` as I -> 0 (and mu(0) = mu_s), phi non-increasing in I
///   (b >= 0), mu non-decreasing in I (mu_2 > mu_s).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "mu_i",
    source = "Chassagne et al. 2023 eqs 1.1-1.2; Maurin, Chauchat & Frey 2016",
    equation = "mu = mu_s + (mu_2 - mu_s)/(i0/I + 1), phi = phi_c/(1 + b I), I = d |gamma_dot| / sqrt(p/rho_p)",
    limits = [Limit::StaticFriction { mu_s: self.mu_s }, Limit::PackingDecreasing, Limit::Increasing]
)]
pub struct MuI {
    /// static friction coefficient (I -> 0)
    #[param(range = "[0, 2]", unit = "-")]
    pub mu_s: f64,
    /// friction coefficient as I -> inf
    #[param(range = "[0, 5]", unit = "-", greater_than = mu_s)]
    pub mu_2: f64,
    /// inertial-number scale I0
    #[param(range = "(0, inf)", unit = "-")]
    pub i0: f64,
    /// volume fraction at I = 0
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_c: f64,
    /// dilatancy coefficient of phi(I)
    #[param(range = "[0, inf)", unit = "-")]
    pub b: f64,
}

impl Default for MuI {
    fn default() -> Self {
        Self { mu_s: 0.35, mu_2: 0.97, i0: 0.69, phi_c: 0.61, b: 0.31 }
    }
}

impl LocalRheology for MuI {
    fn control_name(&self) -> &'static str {
        "i"
    }
    #[inline]
    fn control_number(&self, s: &LocalState) -> f64 {
        s.inertial_number()
    }
    #[inline]
    fn friction(&self, x: f64) -> f64 {
        if x <= 0.0 {
            self.mu_s
        } else {
            // (mu_2 - mu_s) / (I0/I + 1); I = +inf gives I0/I = 0 and mu_2
            self.mu_s + (self.mu_2 - self.mu_s) / (self.i0 / x + 1.0)
        }
    }
    #[inline]
    fn packing(&self, x: f64) -> f64 {
        self.phi_c / (1.0 + self.b * x.max(0.0))
    }
    fn control_of_packing(&self, phi: f64) -> f64 {
        if phi >= self.phi_c {
            0.0
        } else if phi <= 0.0 || self.b == 0.0 || phi.is_nan() {
            f64::INFINITY
        } else {
            (self.phi_c / phi - 1.0) / self.b
        }
    }
    fn pressure_at(&self, s: &LocalState, x: f64) -> f64 {
        // I = d |gamma_dot| sqrt(rho_p / p)  =>  p = rho_p (d gamma_dot / I)^2
        if s.shear_rate == 0.0 || x.is_infinite() {
            0.0
        } else if x <= 0.0 || x.is_nan() {
            f64::INFINITY
        } else {
            let r = s.diameter * s.shear_rate / x;
            s.particle_density * r * r
        }
    }
}

#[typetag::serde(name = "mu_i")]
impl GranularStress for MuI {
    fn as_local(&self) -> Option<&dyn LocalRheology> {
        Some(self)
    }
}

register_model!(Family::Granular, "mu_i", GranularStress, MuI);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn state(gamma: f64, p: f64) -> LocalState {
        LocalState { shear_rate: gamma, pressure: p, diameter: 6e-3, particle_density: 2500.0, fluid_viscosity: 1e-3 }
    }

    #[test]
    fn limits() {
        let m = MuI::default();
        assert_eq!(m.friction(0.0), 0.35);
        assert_relative_eq!(m.friction(1e-12), 0.35, epsilon = 1e-11);
        assert_relative_eq!(m.friction(1e12), 0.97, epsilon = 1e-11);
        assert_eq!(m.friction(f64::INFINITY), 0.97);
        assert_eq!(m.packing(0.0), 0.61);
        assert_eq!(m.packing(f64::INFINITY), 0.0);
        // half-way at I = I0
        assert_relative_eq!(m.friction(0.69), 0.5 * (0.35 + 0.97), max_relative = 1e-15);
    }

    #[test]
    fn control_number() {
        let m = MuI::default();
        assert_relative_eq!(m.control_number(&state(-10.0, 100.0)), 6e-3 * 10.0 * (25.0f64).sqrt());
        assert_eq!(m.control_number(&state(0.0, 0.0)), 0.0);
        assert_eq!(m.control_number(&state(1.0, 0.0)), f64::INFINITY);
        assert!(!m.friction(m.control_number(&state(1.0, 0.0))).is_nan());
    }

    /// The closed-form inverses agree with the trait's generic bisection.
    #[test]
    fn inverses_match_bisection() {
        crate::testing::assert_inverses_match_bisection(&MuI::default(), &state(5.0, 0.0), &[0.05, 0.3, 0.55, 0.6]);
    }

    #[test]
    fn validation() {
        let bad = MuI { mu_2: 0.3, ..MuI::default() };
        assert_eq!(bad.validate().unwrap_err().key, "mu_2");
        let bad = MuI { phi_c: 1.0, ..MuI::default() };
        assert_eq!(bad.validate().unwrap_err().key, "phi_c");
        assert!(MuI::default().validate().is_ok());
    }

    /// docs/verification.md, benchmark 6: on an incline mu(I) = tan a gives I = I0 (tan a - mu_s)/(mu_2 - tan a).
    #[test]
    fn inverse_on_incline() {
        let m = MuI::default();
        let t = 0.5;
        let i = 0.69 * (t - 0.35) / (0.97 - t);
        assert_relative_eq!(m.friction(i), t, max_relative = 1e-14);
    }

    proptest! {
        #[test]
        fn monotone(x in 0.0f64..100.0, f in 1.001f64..10.0) {
            let m = MuI::default();
            prop_assert!(m.friction(x * f + 1e-9) > m.friction(x));
            prop_assert!(m.packing(x * f + 1e-9) < m.packing(x));
            prop_assert!(m.friction(x) >= 0.35 && m.friction(x) < 0.97);
        }

        #[test]
        fn batch_equals_scalar(x in proptest::collection::vec(0.0f64..50.0, 1..64)) {
            crate::testing::assert_batch_equals_scalar(&MuI::default(), &x);
        }
    }
}
