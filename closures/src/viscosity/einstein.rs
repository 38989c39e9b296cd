//! Einstein effective viscosity.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// Einstein (1906, 1911) viscosity of a dilute suspension of spheres
///
/// nu_eff / nu_f = 1 + 5/2 phi
///
/// * Source: Fry et al. 2024 eq 28; Maurin et al. 2015 eq 13; Einstein 1906, Ann. Phys.
///   324, 289 (corrected 1911, Ann. Phys. 339, 591).
/// * Defaults: no parameters (5/2 is the intrinsic viscosity of rigid spheres).
/// * Valid range: theory for phi << 1 in the viscous limit; evaluated for any phi without
///   refusal; `phi_limit` = 1.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "einstein",
    source = "Fry et al. 2024 eq 28; Maurin et al. 2015 eq 13; Einstein 1906/1911",
    equation = "nu_eff / nu_f = 1 + 5/2 phi",
    limits = [Limit::Einstein { coefficient: 2.5 }, Limit::Dilute, Limit::Increasing]
)]
pub struct Einstein {}

#[typetag::serde(name = "einstein")]
impl EffectiveViscosity for Einstein {
    #[inline]
    fn ratio(&self, phi: f64) -> f64 {
        1.0 + 2.5 * phi
    }
}

register_model!(Family::Viscosity, "einstein", EffectiveViscosity, Einstein);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn values_and_einstein_slope() {
        let v = Einstein::default();
        assert_eq!(v.ratio(0.0), 1.0);
        assert_relative_eq!(v.ratio(0.1), 1.25, max_relative = 1e-15);
        for h in [1e-3, 1e-6, 1e-9] {
            assert_relative_eq!((v.ratio(h) - 1.0) / h, 2.5, max_relative = 1e-6);
        }
        assert_eq!(v.phi_limit(), 1.0);
        assert!(v.validate().is_ok());
    }

    proptest! {
        #[test]
        fn increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04) {
            let v = Einstein::default();
            prop_assert!(v.ratio(phi + dphi) > v.ratio(phi));
        }
    }
}
