//! No hindrance.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragReynolds, Hindrance, Limit};
use serde::{Deserialize, Serialize};

/// No hindrance: the drag on a particle in a suspension is the single-particle drag
///
/// f(phi, Re_p) = 1
///
/// * Source: the dilute limit phi -> 0 of every hindrance law (e.g. Maurin et al. 2015
///   eq 12 and Chassagne et al. 2023 eq 2.10 with zeta = 0).
/// * Defaults: no parameters.
/// * Valid range: dilute suspensions; any phi in [0, 1) and Re_p >= 0. C_D is evaluated
///   at the interstitial Re_p.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "none",
    source = "dilute limit of Maurin et al. 2015 eq 12 / Chassagne et al. 2023 eq 2.10",
    equation = "f = 1",
    limits = [Limit::Dilute]
)]
pub struct NoHindrance {}

#[typetag::serde(name = "none")]
impl Hindrance for NoHindrance {
    #[inline]
    fn factor(&self, _phi: f64, _re_p: f64) -> f64 {
        1.0
    }
    fn reynolds_convention(&self) -> DragReynolds {
        DragReynolds::Interstitial
    }
    fn depends_on_reynolds(&self) -> bool {
        false
    }
}

register_model!(Family::Hindrance, "none", Hindrance, NoHindrance);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn is_one_and_interstitial() {
        let h = NoHindrance::default();
        assert_eq!(h.factor(0.0, 0.0), 1.0);
        assert_eq!(h.factor(0.6, 100.0), 1.0);
        assert_eq!(h.drag_reynolds(0.6, 100.0), 100.0);
        assert!(h.validate().is_ok());
        assert!(toml::from_str::<NoHindrance>("exponent = 3.1").is_err());
    }

    proptest! {
        #[test]
        fn tends_to_one_as_phi_vanishes(phi in 0f64..1e-6, re in 0f64..1e5) {
            prop_assert_eq!(NoHindrance::default().factor(phi, re), 1.0);
        }
    }
}
