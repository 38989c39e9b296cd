//! Stokes drag law.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragLaw, Limit};
use serde::{Deserialize, Serialize};

/// Stokes (1851) drag coefficient of a sphere in creeping flow
///
/// C_D = 24 / Re_p
///
/// * Source: G. G. Stokes 1851, "On the effect of the internal friction of fluids on the
///   motion of pendulums", Trans. Camb. Phil. Soc. 9, 8-106 (the viscous limit of every
///   other drag law in this family).
/// * Defaults: no parameters.
/// * Valid range: Re_p << 1 (within 10 % of the standard drag curve only for Re_p below
///   about 0.5); `cd_re` is exactly 24 for every Re_p and `cd_inf` is 0.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "stokes",
    source = "Stokes 1851, Trans. Camb. Phil. Soc. 9, 8-106",
    equation = "C_D = 24 / Re_p",
    limits = [Limit::Stokes { cd_re: 24.0 }, Limit::HighReynolds, Limit::Decreasing]
)]
pub struct Stokes {}

#[typetag::serde(name = "stokes")]
impl DragLaw for Stokes {
    #[inline]
    fn cd(&self, re_p: f64) -> f64 {
        24.0 / re_p
    }
    #[inline]
    fn cd_re(&self, _re_p: f64) -> f64 {
        24.0
    }
    fn cd_inf(&self) -> f64 {
        0.0
    }
}

register_model!(Family::Drag, "stokes", DragLaw, Stokes);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn cd_re_is_exactly_24_and_cd_inf_is_zero() {
        let s = Stokes::default();
        assert_eq!(s.cd_re(0.0), 24.0);
        assert_eq!(s.cd_re(1e-300), 24.0);
        assert_eq!(s.cd_inf(), 0.0);
        assert!(s.params().is_empty());
        assert!(s.validate().is_ok());
    }

    #[test]
    fn cd_times_re_tends_to_24() {
        let s = Stokes::default();
        for re in [1e-12, 1e-8, 1e-4, 1e-2] {
            assert_relative_eq!(s.cd(re) * re, 24.0, max_relative = 1e-14);
        }
    }

    #[test]
    fn unknown_field_is_refused() {
        assert!(toml::from_str::<Stokes>("a = 24.0").is_err());
        assert_eq!(toml::from_str::<Stokes>("").unwrap(), Stokes::default());
    }

    proptest! {
        #[test]
        fn decreasing_in_re(re in 1e-8f64..1e8, f in 1.01f64..10.0) {
            let s = Stokes::default();
            prop_assert!(s.cd(re * f) < s.cd(re));
        }
    }
}
