//! mu(K) local rheology (viscous-inertial).

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, GranularStress, Limit, LocalRheology, LocalState};
use serde::{Deserialize, Serialize};

/// mu(K) rheology unifying the viscous and inertial regimes (Trulsson et al. 2012)
///
/// ```text
/// J = |gamma_dot| eta_f / p,  I = d |gamma_dot| / sqrt(p/rho_p),  K = J + alpha I^2
/// phi(K) = phi_c / (1 + b sqrt(K))
/// mu(K)  = mu_1 + (mu_2 - mu_1) / (1 + sqrt(K0/K))
/// mu(phi) = mu_1 + (mu_2 - mu_1)(phi_c - phi) / (phi_c - (1 - b sqrt(K0)) phi)   (steady)
/// ```
///
/// * Source: Fry, Lacaze et al. 2024 eqs 34-39 (global fit of section IV B 2, fig. 11).
/// * Defaults: `phi_c = 0.615`, `b = 0.7`, `mu_1 = 0.23`, `mu_2 = 0.75`, `sqrt_k0 = 0.18`
///   (the parameter is sqrt(K0), as the paper reports it), `alpha = 0.635` (Trulsson 2012).
///   Trulsson's 2D values: `mu_1 = 0.277`, `mu_2 = 0.85`, `sqrt_k0 = 0.29`.
/// * Valid range: `phi_c` in (0, 1), `b > 0`, `mu_1` in [0, 2], `mu_2` in [0, 5] with
///   `mu_2 > mu_1`, `sqrt_k0 > 0`, `alpha >= 0`; K >= 0.
/// * Decisions: K = 0 when |gamma_dot| = 0; K = +inf when p <= 0 and |gamma_dot| > 0
///   (mu = mu_2, phi = 0), as for `mu_i`. mu(phi) is clamped to phi in [0, phi_c]
///   (mu_2 at phi = 0, mu_1 at and above phi_c).
/// * Declared limits: mu -> `mu_1`, the quasi-static friction, as K -> 0 (and mu(0) = mu_1;
///   mu - mu_1 ~ sqrt(K / K0) on the way), phi non-increasing in K (b > 0), mu
///   non-decreasing in K (mu_2 > mu_1).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "mu_k",
    source = "Fry, Lacaze et al. 2024 eqs 34-39; Trulsson, Andreotti & Claudin 2012",
    equation = "mu = mu_1 + (mu_2 - mu_1)/(1 + sqrt(K0/K)), phi = phi_c/(1 + b sqrt(K)), K = |gamma_dot| eta_f/p + alpha I^2",
    limits = [Limit::StaticFriction { mu_s: self.mu_1 }, Limit::PackingDecreasing, Limit::Increasing]
)]
pub struct MuK {
    /// jamming volume fraction (K = 0)
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_c: f64,
    /// dilatancy coefficient of phi(K)
    #[param(range = "(0, inf)", unit = "-")]
    pub b: f64,
    /// friction coefficient as K -> 0
    #[param(range = "[0, 2]", unit = "-")]
    pub mu_1: f64,
    /// friction coefficient as K -> inf
    #[param(range = "[0, 5]", unit = "-", greater_than = mu_1)]
    pub mu_2: f64,
    /// sqrt(K0) of mu(K)
    #[param(range = "(0, inf)", unit = "-")]
    pub sqrt_k0: f64,
    /// weight of I^2 in K = J + alpha I^2
    #[param(range = "[0, inf)", unit = "-")]
    pub alpha: f64,
}

impl Default for MuK {
    fn default() -> Self {
        Self { phi_c: 0.615, b: 0.7, mu_1: 0.23, mu_2: 0.75, sqrt_k0: 0.18, alpha: 0.635 }
    }
}

impl MuK {
    /// Steady-state friction as a function of the volume fraction, Fry et al. eq 39
    /// (K eliminated between eqs 37 and 38); phi clamped to [0, phi_c].
    pub fn friction_of_packing(&self, phi: f64) -> f64 {
        let phi = phi.clamp(0.0, self.phi_c);
        self.mu_1 + (self.mu_2 - self.mu_1) * (self.phi_c - phi) / (self.phi_c - (1.0 - self.b * self.sqrt_k0) * phi)
    }

    /// Control number K whose packing is `phi` (inverse of eq 37), for phi in (0, phi_c].
    pub fn control_of_packing(&self, phi: f64) -> f64 {
        let s = (self.phi_c / phi - 1.0) / self.b;
        s * s
    }
}

impl LocalRheology for MuK {
    fn control_name(&self) -> &'static str {
        "k"
    }
    #[inline]
    fn control_number(&self, s: &LocalState) -> f64 {
        // K = J + alpha I^2, eq 36
        let (i, j) = (s.inertial_number(), s.viscous_number());
        if j.is_infinite() {
            // sheared at zero pressure; alpha = 0 must not turn 0 * inf into NaN
            return f64::INFINITY;
        }
        j + self.alpha * i * i
    }
    #[inline]
    fn friction(&self, x: f64) -> f64 {
        if x <= 0.0 {
            self.mu_1
        } else {
            // sqrt(K0/K) = 0 at K = +inf gives mu_2
            self.mu_1 + (self.mu_2 - self.mu_1) / (1.0 + self.sqrt_k0 / x.sqrt())
        }
    }
    #[inline]
    fn packing(&self, x: f64) -> f64 {
        self.phi_c / (1.0 + self.b * x.max(0.0).sqrt())
    }
    fn control_of_packing(&self, phi: f64) -> f64 {
        if phi >= self.phi_c {
            0.0
        } else if phi <= 0.0 || phi.is_nan() {
            f64::INFINITY
        } else {
            MuK::control_of_packing(self, phi)
        }
    }
    fn pressure_at(&self, s: &LocalState, x: f64) -> f64 {
        // K = (eta_f |gamma_dot| + alpha rho_p d^2 gamma_dot^2) / p, eq 36
        let g = s.shear_rate.abs();
        if g == 0.0 || x.is_infinite() {
            0.0
        } else if x <= 0.0 || x.is_nan() {
            f64::INFINITY
        } else {
            (s.fluid_viscosity * g + self.alpha * s.particle_density * s.diameter * s.diameter * g * g) / x
        }
    }
}

#[typetag::serde(name = "mu_k")]
impl GranularStress for MuK {
    fn as_local(&self) -> Option<&dyn LocalRheology> {
        Some(self)
    }
}

register_model!(Family::Granular, "mu_k", GranularStress, MuK);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn limits() {
        let m = MuK::default();
        assert_eq!(m.friction(0.0), 0.23);
        assert_relative_eq!(m.friction(1e-16), 0.23, epsilon = 1e-6);
        assert_relative_eq!(m.friction(1e16), 0.75, epsilon = 1e-6);
        assert_eq!(m.friction(f64::INFINITY), 0.75);
        assert_eq!(m.packing(0.0), 0.615);
        assert_eq!(m.packing(f64::INFINITY), 0.0);
        assert_relative_eq!(m.friction(0.18 * 0.18), 0.5 * (0.23 + 0.75), max_relative = 1e-14);
        assert_eq!(m.friction_of_packing(0.0), 0.75);
        assert_eq!(m.friction_of_packing(0.615), 0.23);
        assert_eq!(m.friction_of_packing(0.7), 0.23);
    }

    #[test]
    fn control_number() {
        let m = MuK::default();
        let s = LocalState {
            shear_rate: -20.0,
            pressure: 50.0,
            diameter: 1e-3,
            particle_density: 2500.0,
            fluid_viscosity: 1e-3,
        };
        let j = 20.0 * 1e-3 / 50.0;
        let i = 1e-3 * 20.0 / (50.0f64 / 2500.0).sqrt();
        assert_relative_eq!(m.control_number(&s), j + 0.635 * i * i, max_relative = 1e-14);
        assert_eq!(m.control_number(&LocalState { pressure: 0.0, ..s }), f64::INFINITY);
        assert_eq!(m.control_number(&LocalState { shear_rate: 0.0, pressure: 0.0, ..s }), 0.0);
    }

    /// The closed-form inverses agree with the trait's generic bisection.
    #[test]
    fn inverses_match_bisection() {
        let s = LocalState {
            shear_rate: 3.0,
            pressure: 0.0,
            diameter: 1e-3,
            particle_density: 2500.0,
            fluid_viscosity: 1e-3,
        };
        crate::testing::assert_inverses_match_bisection(&MuK::default(), &s, &[0.05, 0.3, 0.55, 0.61]);
    }

    #[test]
    fn validation() {
        let bad = MuK { mu_2: 0.2, ..MuK::default() };
        assert_eq!(bad.validate().unwrap_err().key, "mu_2");
        let bad = MuK { sqrt_k0: 0.0, ..MuK::default() };
        assert_eq!(bad.validate().unwrap_err().key, "sqrt_k0");
        assert!(MuK::default().validate().is_ok());
    }

    proptest! {
        #[test]
        fn eq39_is_eq38_of_eq37_inverse(phi in 1e-3f64..0.615, mu_1 in 0.1f64..0.5, dmu in 0.01f64..1.0, b in 0.2f64..2.0, sk0 in 0.05f64..0.5) {
            let m = MuK { mu_1, mu_2: mu_1 + dmu, b, sqrt_k0: sk0, ..MuK::default() };
            let k = m.control_of_packing(phi);
            prop_assert!((m.packing(k) - phi).abs() <= 1e-12);
            prop_assert!((m.friction_of_packing(phi) - m.friction(k)).abs() <= 1e-12);
        }

        #[test]
        fn monotone(x in 0.0f64..100.0, f in 1.001f64..10.0) {
            let m = MuK::default();
            prop_assert!(m.friction(x * f + 1e-9) > m.friction(x));
            prop_assert!(m.packing(x * f + 1e-9) < m.packing(x));
            prop_assert!(m.friction(x) >= 0.23 && m.friction(x) < 0.75);
        }

        #[test]
        fn batch_equals_scalar(x in proptest::collection::vec(0.0f64..50.0, 1..64)) {
            crate::testing::assert_batch_equals_scalar(&MuK::default(), &x);
        }
    }
}
