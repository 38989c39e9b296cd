//! Krieger-Dougherty effective viscosity.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// Krieger & Dougherty (1959) viscosity of a dense suspension
///
/// nu_eff / nu_f = (1 - phi/phi_m)^(-\[eta\] phi_m)
///
/// * Source: Fry et al. 2024 eq 30 (and their figure 12 / table II / figure 14);
///   Krieger & Dougherty 1959, Trans. Soc. Rheol. 3, 137-152. Eq 30 prints the exponent
///   -3/2 phi_m: a typo (docs/verification.md); the paper's figures and fits, and Krieger &
///   Dougherty, use the intrinsic viscosity \[eta\] = 5/2 of spheres.
/// * Defaults: `phi_m = 0.62` (Fry et al. eq 30; their fits give 0.62 +- 0.02),
///   `intrinsic = 2.5`.
/// * Valid range: `phi_m` in (0, 1), `intrinsic` in (0, 10]. Diverges at phi = phi_m:
///   `phi_limit` = phi_m and `ratio` returns `f64::INFINITY` for phi >= phi_m (a solver
///   must keep phi below phi_m or cap the ratio itself). Small-phi slope = `intrinsic`
///   (Einstein's 5/2 with the default).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "krieger_dougherty",
    source = "Fry et al. 2024 eq 30 (exponent 5/2 phi_m, printed 3/2 is a typo); Krieger & Dougherty 1959",
    equation = "nu_eff / nu_f = (1 - phi/phi_m)^(-intrinsic phi_m)",
    limits = [Limit::Einstein { coefficient: self.intrinsic }, Limit::Dilute, Limit::Increasing]
)]
pub struct KriegerDougherty {
    /// volume fraction at which the viscosity diverges
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_m: f64,
    /// intrinsic viscosity \[eta\] (5/2 for spheres)
    #[param(range = "(0, 10]", unit = "-")]
    pub intrinsic: f64,
}

impl Default for KriegerDougherty {
    fn default() -> Self {
        Self { phi_m: 0.62, intrinsic: 2.5 }
    }
}

#[typetag::serde(name = "krieger_dougherty")]
impl EffectiveViscosity for KriegerDougherty {
    #[inline]
    fn ratio(&self, phi: f64) -> f64 {
        if phi >= self.phi_m {
            f64::INFINITY
        } else {
            (1.0 - phi / self.phi_m).powf(-self.intrinsic * self.phi_m)
        }
    }
    fn phi_limit(&self) -> f64 {
        self.phi_m
    }
}

register_model!(Family::Viscosity, "krieger_dougherty", EffectiveViscosity, KriegerDougherty);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn values_and_divergence() {
        let v = KriegerDougherty::default();
        assert_eq!(v.ratio(0.0), 1.0);
        // (1 - 0.31/0.62)^(-2.5 * 0.62) = 0.5^(-1.55)
        assert_relative_eq!(v.ratio(0.31), 2f64.powf(1.55), max_relative = 1e-14);
        assert_eq!(v.phi_limit(), 0.62);
        assert_eq!(v.ratio(0.62), f64::INFINITY);
        assert_eq!(v.ratio(0.7), f64::INFINITY);
        assert!(v.ratio(0.619_999).is_finite());
    }

    #[test]
    fn einstein_slope_with_intrinsic_2_5() {
        let v = KriegerDougherty::default();
        for h in [1e-4, 1e-6, 1e-8] {
            assert_relative_eq!((v.ratio(h) - 1.0) / h, 2.5, max_relative = 1e-3);
        }
        let v = KriegerDougherty { phi_m: 0.55, intrinsic: 4.0 };
        assert_relative_eq!((v.ratio(1e-8) - 1.0) / 1e-8, 4.0, max_relative = 1e-6);
    }

    #[test]
    fn validate_refuses_out_of_range() {
        for bad in [0.0, 1.0, 1.2, -0.1, f64::NAN] {
            let e = KriegerDougherty { phi_m: bad, ..Default::default() }.validate().unwrap_err();
            assert_eq!(e.key, "phi_m");
        }
        for bad in [0.0, -2.5, 10.5, f64::INFINITY] {
            let e = KriegerDougherty { intrinsic: bad, ..Default::default() }.validate().unwrap_err();
            assert_eq!(e.key, "intrinsic");
        }
        assert!(KriegerDougherty::default().validate().is_ok());
    }

    #[test]
    fn parses_from_toml() {
        let v: KriegerDougherty = toml::from_str("phi_m = 0.585").unwrap();
        assert_eq!(v, KriegerDougherty { phi_m: 0.585, intrinsic: 2.5 });
        assert!(toml::from_str::<KriegerDougherty>("phi_max = 0.6").is_err());
    }

    proptest! {
        #[test]
        fn increasing(phi in 0f64..0.55, dphi in 1e-4f64..0.04, phi_m in 0.6f64..0.99, k in 0.1f64..=10.0) {
            let v = KriegerDougherty { phi_m, intrinsic: k };
            prop_assert!(v.ratio(phi + dphi) > v.ratio(phi));
            prop_assert!(v.ratio(phi) >= 1.0);
        }
    }
}
