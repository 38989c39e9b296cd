//! Dallavalle drag law.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragLaw, Limit};
use serde::{Deserialize, Serialize};

/// Dallavalle (1943) drag coefficient
///
/// C_D = C_D^inf + a / Re_p
///
/// * Source: Chassagne et al. 2023 eq 2.11a; Maurin et al. 2015 eq 12 (with the
///   hindrance factor split off into [`crate::hindrance`]).
/// * Defaults: `cd_inf = 0.4`, `a = 24.4` (the papers' values; one DEM code uses 0.44).
/// * Valid range: `cd_inf` in [0, 10], `a` in (0, 100]; any Re_p > 0. Tends to C_D^inf at
///   large Re_p and to a / Re_p (slightly above Stokes' 24/Re_p) at small Re_p.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "dallavalle",
    source = "Chassagne et al. 2023 eq 2.11; Maurin et al. 2015 eq 12",
    equation = "C_D = cd_inf + a / Re_p",
    limits = [Limit::Stokes { cd_re: self.a }, Limit::HighReynolds, Limit::Decreasing]
)]
pub struct Dallavalle {
    /// drag coefficient at infinite Re_p
    #[param(range = "[0, 10]", unit = "-")]
    pub cd_inf: f64,
    /// viscous coefficient of a/Re_p
    #[param(range = "(0, 100]", unit = "-")]
    pub a: f64,
}

impl Default for Dallavalle {
    fn default() -> Self {
        Self { cd_inf: 0.4, a: 24.4 }
    }
}

#[typetag::serde(name = "dallavalle")]
impl DragLaw for Dallavalle {
    #[inline]
    fn cd(&self, re_p: f64) -> f64 {
        self.cd_inf + self.a / re_p
    }
    #[inline]
    fn cd_re(&self, re_p: f64) -> f64 {
        self.cd_inf * re_p + self.a
    }
    fn cd_inf(&self) -> f64 {
        self.cd_inf
    }
}

register_model!(Family::Drag, "dallavalle", DragLaw, Dallavalle);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    /// docs/verification.md, benchmark 4: terminal velocity, exact root of
    /// 0.4 w^2 + 24.4 nu w / d = (4/3)(s-1) g d.
    fn terminal_velocity(d: f64, s: f64, nu: f64) -> f64 {
        // Solve the force balance with the drag law itself (bisection), not the closed form.
        let law = Dallavalle::default();
        let g = 9.81;
        let residual = |w: f64| 0.75 * law.cd(w * d / nu) * w * w / d - (s - 1.0) * g;
        let (mut lo, mut hi) = (1e-12, 10.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if residual(mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn terminal_velocities_of_verification_md() {
        assert_relative_eq!(terminal_velocity(6e-3, 2.5, 1e-6), 0.53743, max_relative = 1e-4);
        assert_relative_eq!(terminal_velocity(1e-4, 2.65, 1e-6), 8.7204e-3, max_relative = 1e-4);
    }

    proptest! {
        #[test]
        fn tends_to_cd_inf_at_large_re(re in 1e7f64..1e12) {
            let d = Dallavalle::default();
            prop_assert!((d.cd(re) - 0.4).abs() < 1e-5);
        }

        #[test]
        fn decreasing_in_re_and_cd_re_consistent(re in 1e-6f64..1e6, f in 1.01f64..10.0) {
            let d = Dallavalle::default();
            prop_assert!(d.cd(re * f) < d.cd(re));
            prop_assert!((d.cd_re(re) - d.cd(re) * re).abs() <= 1e-12 * d.cd_re(re).max(1.0));
        }
    }

    #[test]
    fn small_re_limit_is_a_over_re() {
        let d = Dallavalle::default();
        assert_relative_eq!(d.cd_re(0.0), 24.4);
    }
}
