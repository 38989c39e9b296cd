//! Clear-fluid viscosity.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// The fluid phase keeps the clear-fluid viscosity
///
/// nu_eff / nu_f = 1
///
/// * Source: Chassagne et al. 2023 eq 2.7 (fluid stress with the clear-fluid viscosity).
/// * Defaults: no parameters.
/// * Valid range: any phi; `phi_limit` = 1.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "clear_fluid",
    source = "Chassagne et al. 2023 eq 2.7",
    equation = "nu_eff / nu_f = 1",
    limits = [Limit::Dilute]
)]
pub struct ClearFluid {}

#[typetag::serde(name = "clear_fluid")]
impl EffectiveViscosity for ClearFluid {
    #[inline]
    fn ratio(&self, _phi: f64) -> f64 {
        1.0
    }
}

register_model!(Family::Viscosity, "clear_fluid", EffectiveViscosity, ClearFluid);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn is_one() {
        let v = ClearFluid::default();
        assert_eq!(v.ratio(0.0), 1.0);
        assert_eq!(v.ratio(0.6), 1.0);
        assert_eq!(v.phi_limit(), 1.0);
        assert!(v.validate().is_ok());
        assert!(toml::from_str::<ClearFluid>("beta = 2.8").is_err());
    }

    proptest! {}
}
