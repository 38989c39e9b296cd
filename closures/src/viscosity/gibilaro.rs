//! Gibilaro power-law viscosity of the fluid phase.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// Gibilaro et al. (2007) apparent viscosity of the fluid phase of a fluidised bed
///
/// nu_eff / nu_f = (1 - phi)^(-beta)
///
/// * Source: Fry et al. 2024 eq 32; Gibilaro, Gallucci, Di Felice & Pagliai 2007, Chem.
///   Eng. Sci. 62, 294-300.
/// * Defaults: `beta = 2.8` (Gibilaro et al.; Fry et al. fit 1.71 for their bedload case
///   at Re_p = 1, theta = 0.67, see the `fry2024` model).
/// * Valid range: `beta` in [0, 20]; phi in [0, 1), `phi_limit` = 1. Small-phi limit
///   1 + beta phi: *not* Einstein's 1 + 5/2 phi (Fry et al.: "it does not satisfy
///   theoretical models when developed at small phi").
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "gibilaro",
    source = "Fry et al. 2024 eq 32; Gibilaro et al. 2007, Chem. Eng. Sci. 62, 294",
    equation = "nu_eff / nu_f = (1 - phi)^(-beta)",
    limits = [Limit::Dilute, Limit::Increasing]
)]
pub struct Gibilaro {
    /// exponent beta of (1-phi)^(-beta)
    #[param(range = "[0, 20]", unit = "-")]
    pub beta: f64,
}

impl Default for Gibilaro {
    fn default() -> Self {
        Self { beta: 2.8 }
    }
}

#[typetag::serde(name = "gibilaro")]
impl EffectiveViscosity for Gibilaro {
    #[inline]
    fn ratio(&self, phi: f64) -> f64 {
        (1.0 - phi).powf(-self.beta)
    }
}

register_model!(Family::Viscosity, "gibilaro", EffectiveViscosity, Gibilaro);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn values_and_slope_is_beta_not_einstein() {
        let v = Gibilaro::default();
        assert_eq!(v.ratio(0.0), 1.0);
        assert_relative_eq!(v.ratio(0.5), 2f64.powf(2.8), max_relative = 1e-15);
        for h in [1e-4, 1e-6, 1e-8] {
            assert_relative_eq!((v.ratio(h) - 1.0) / h, 2.8, max_relative = 1e-3);
        }
        assert_eq!(v.phi_limit(), 1.0);
    }

    #[test]
    fn validate_refuses_out_of_range_beta() {
        for bad in [-0.1, 20.5, f64::NAN] {
            let e = Gibilaro { beta: bad }.validate().unwrap_err();
            assert_eq!(e.key, "beta");
        }
        assert!(Gibilaro { beta: 0.0 }.validate().is_ok());
        assert!(Gibilaro::default().validate().is_ok());
    }

    proptest! {
        #[test]
        fn increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04, beta in 0.1f64..=20.0) {
            let v = Gibilaro { beta };
            prop_assert!(v.ratio(phi + dphi) > v.ratio(phi));
        }
    }
}
