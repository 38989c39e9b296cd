//! Batchelor-Green effective viscosity.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// Batchelor & Green (1972) second-order viscosity of a suspension of spheres in shear
///
/// nu_eff / nu_f = 1 + 5/2 phi + 7.6 phi^2
///
/// * Source: Fry et al. 2024 eq 29; Batchelor & Green 1972, J. Fluid Mech. 56, 401-427.
/// * Defaults: no parameters.
/// * Valid range: viscous limit, phi <= ~0.1 (Fry et al.). Larger phi is evaluated without
///   refusal (the polynomial stays finite and increasing); `phi_limit` = 1.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "batchelor_green",
    source = "Fry et al. 2024 eq 29; Batchelor & Green 1972, J. Fluid Mech. 56, 401",
    equation = "nu_eff / nu_f = 1 + 5/2 phi + 7.6 phi^2",
    limits = [Limit::Einstein { coefficient: 2.5 }, Limit::Dilute, Limit::Increasing]
)]
pub struct BatchelorGreen {}

#[typetag::serde(name = "batchelor_green")]
impl EffectiveViscosity for BatchelorGreen {
    #[inline]
    fn ratio(&self, phi: f64) -> f64 {
        1.0 + phi * (2.5 + 7.6 * phi)
    }
}

register_model!(Family::Viscosity, "batchelor_green", EffectiveViscosity, BatchelorGreen);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn values_and_einstein_slope() {
        let v = BatchelorGreen::default();
        assert_eq!(v.ratio(0.0), 1.0);
        assert_relative_eq!(v.ratio(0.1), 1.0 + 0.25 + 0.076, max_relative = 1e-15);
        for h in [1e-4, 1e-6, 1e-8] {
            assert_relative_eq!((v.ratio(h) - 1.0) / h, 2.5, max_relative = 1e-3);
        }
        // no refusal beyond the range of validity
        assert!(v.ratio(0.5).is_finite());
        assert!(v.validate().is_ok());
    }

    proptest! {
        #[test]
        fn increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04) {
            let v = BatchelorGreen::default();
            prop_assert!(v.ratio(phi + dphi) > v.ratio(phi));
        }
    }
}
