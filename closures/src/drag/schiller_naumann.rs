//! Schiller-Naumann drag law.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragLaw, Limit};
use serde::{Deserialize, Serialize};

/// Reynolds number above which the Schiller-Naumann C_D is held at its Newton value.
pub const RE_NEWTON: f64 = 1000.0;

/// C_D of the Newton regime (Re_p >= 1000).
pub const CD_NEWTON: f64 = 0.44;

/// Schiller & Naumann (1933) drag coefficient of a sphere
///
/// C_D = 24/Re_p (1 + 0.15 Re_p^0.687)  for Re_p < 1000,
/// C_D = 0.44                           for Re_p >= 1000.
///
/// * Source: L. Schiller & A. Naumann 1933, "Ueber die grundlegenden Berechnungen bei der
///   Schwerkraftaufbereitung", Z. Ver. Dtsch. Ing. 77, 318-320. Not used in the four
///   reference papers; included as the standard sphere correlation of CFD-DEM codes.
/// * Defaults: no parameters (the constants 0.15, 0.687, 1000 and 0.44 belong to the
///   correlation).
/// * Valid range: sphere, Re_p < 2e5 (below the drag crisis). `cd_inf` = 0.44.
///   C_D decreases with Re_p below 1000; at Re_p = 1000 the correlation jumps from
///   0.4383 to 0.44 (a 0.4 % step, as in every implementation of it).
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "schiller_naumann",
    source = "Schiller & Naumann 1933, Z. Ver. Dtsch. Ing. 77, 318-320",
    equation = "C_D = 24/Re_p (1 + 0.15 Re_p^0.687) for Re_p < 1000, 0.44 otherwise",
    limits = [Limit::Stokes { cd_re: 24.0 }, Limit::HighReynolds]
)]
pub struct SchillerNaumann {}

#[typetag::serde(name = "schiller_naumann")]
impl DragLaw for SchillerNaumann {
    #[inline]
    fn cd(&self, re_p: f64) -> f64 {
        if re_p < RE_NEWTON {
            24.0 / re_p * (1.0 + 0.15 * re_p.powf(0.687))
        } else {
            CD_NEWTON
        }
    }
    #[inline]
    fn cd_re(&self, re_p: f64) -> f64 {
        if re_p < RE_NEWTON {
            24.0 * (1.0 + 0.15 * re_p.powf(0.687))
        } else {
            CD_NEWTON * re_p
        }
    }
    fn cd_inf(&self) -> f64 {
        CD_NEWTON
    }
}

register_model!(Family::Drag, "schiller_naumann", DragLaw, SchillerNaumann);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn stokes_limit_and_hand_values() {
        let s = SchillerNaumann::default();
        assert_eq!(s.cd_re(0.0), 24.0);
        assert_relative_eq!(s.cd_re(1e-10), 24.0, max_relative = 1e-7);
        // 24 (1 + 0.15) = 27.6 at Re = 1; 0.24 (1 + 0.15 * 100^0.687) at Re = 100.
        assert_relative_eq!(s.cd(1.0), 27.6, max_relative = 1e-15);
        assert_relative_eq!(s.cd(100.0), 1.091_731_091_094_873, max_relative = 1e-12);
        assert_eq!(s.cd_inf(), 0.44);
        assert!(s.validate().is_ok());
    }

    #[test]
    fn newton_regime_is_constant() {
        let s = SchillerNaumann::default();
        for re in [1000.0, 1e4, 1e6, 1e12] {
            assert_eq!(s.cd(re), 0.44);
        }
        // the jump at Re = 1000 is small
        assert!((s.cd(999.999) - 0.44).abs() < 0.005);
    }

    proptest! {
        #[test]
        fn decreasing_below_1000(re in 1e-6f64..900.0, f in 1.001f64..1.1) {
            let s = SchillerNaumann::default();
            prop_assert!(s.cd(re * f) < s.cd(re));
        }

        #[test]
        fn cd_re_consistent(re in 1e-6f64..1e6) {
            let s = SchillerNaumann::default();
            prop_assert!((s.cd_re(re) - s.cd(re) * re).abs() <= 1e-12 * s.cd_re(re).max(1.0));
        }
    }
}
