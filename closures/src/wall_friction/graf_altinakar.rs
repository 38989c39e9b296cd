//! Graf & Altinakar smooth-wall friction.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, Limit, WallFriction};
use serde::{Deserialize, Serialize};

/// Reynolds number |U| W / nu_f below which the friction factor is the laminar 48 / Re:
/// where 48 / Re equals the Graf-Altinakar law (to 1e-9, test
/// `is_continuous_at_the_laminar_switch`).
pub const RE_LAMINAR: f64 = 617.970_325_458_568;

/// Darcy-Weisbach friction factor of a smooth wall, Graf & Altinakar (1998)
///
/// 1/sqrt(f) = 2 log10(Re sqrt(f) / 4) + 0.32   (turbulent, Re > 618)
/// f = 48 / Re                                  (laminar, Re <= 618)
///
/// with Re = |U| W / nu_f built on the channel width W.
///
/// * Source: Maurin et al. 2015 section III B, the correction of the Frey flume's smooth
///   glass walls "evaluated from the classical Einstein method with a Graf and Altinakar
///   friction factor" (their refs 50, 51). The paper names the law without writing it; the
///   form and the Reynolds number on the width are those of the authors' implementation
///   (YADE `HydroForceEngine::fluidWallFriction`, `wallFrictionModel = 1`); the textbook
///   itself (Graf & Altinakar 1998, Fluvial Hydraulics, Wiley) could not be read. The
///   laminar branch is the exact plane-Poiseuille wall stress 6 mu U / W between two
///   plates W apart (f = 96 / Re on the hydraulic diameter 2W), switched where the two
///   laws cross so that f is continuous; the transitional regime is not modelled.
/// * Defaults: `coefficient = 1` (the law above). `coefficient` multiplies f (both
///   branches), as YADE's `fluidFrictionCoef`. The peer code's own solver
///   (`HydroForceEngine::calWallFriction` in 2017, the fluid resolution of 2020) iterates
///   1/sqrt(f) = 2 ln(Re sqrt(f)) + 0.32 with the natural logarithm and without the 1/4,
///   which gives 0.16-0.18 of this law over the Frey flume's Re = 2000-8000 (test
///   `the_peer_codes_natural_log_law_is_a_sixth_of_it_in_the_frey_range`): `coefficient =
///   0.17` stands for it there.
/// * Valid range: `coefficient` in (0, 10]; smooth walls (glass, perspex), any Re >= 0. Over the Frey flume (U =
///   0.4-1 m/s in a 6.5 mm channel, Re = 2600-6500) f = 0.036-0.047, within 7 % of
///   Blasius' 0.3164 Re^-1/4 (test `agrees_with_blasius_in_its_range`, 3e3 <= Re <= 1e5).
///   The turbulent root is found by Newton's method on ln(1/sqrt f), where the law is
///   convex and monotone, to round-off.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "graf_altinakar",
    source = "Maurin et al. 2015 section III B; Graf & Altinakar 1998 (form of YADE HydroForceEngine)",
    equation = "1/sqrt(f) = 2 log10(Re sqrt(f) / 4) + 0.32, Re > 618; f = 48 / Re below; times coefficient",
    limits = [Limit::Decreasing]
)]
pub struct GrafAltinakar {
    /// factor on the friction factor
    #[serde(skip_serializing_if = "is_one")]
    #[param(range = "(0, 10]", unit = "-")]
    pub coefficient: f64,
}

impl Default for GrafAltinakar {
    fn default() -> Self {
        Self { coefficient: 1.0 }
    }
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

#[typetag::serde(name = "graf_altinakar")]
impl WallFriction for GrafAltinakar {
    fn poiseuille_number(&self, re: f64) -> f64 {
        if re <= RE_LAMINAR {
            return 48.0 * self.coefficient;
        }
        // with y = ln(1/sqrt f): e^y + a y = c, a = 2 / ln 10, c = a ln(Re / 4) + 0.32,
        // convex and increasing in y: Newton converges from any start (monotonically after
        // the first step)
        let a = 2.0 / std::f64::consts::LN_10;
        let c = a * (0.25 * re).ln() + 0.32;
        let mut y = c.max(1.0).ln();
        for _ in 0..60 {
            let e = y.exp();
            let step = (e + a * y - c) / (e + a);
            y -= step;
            if step.abs() <= 1e-15 * y.abs().max(1.0) {
                break;
            }
        }
        (-2.0 * y).exp() * re * self.coefficient
    }
}

register_model!(Family::WallFriction, "graf_altinakar", WallFriction, GrafAltinakar);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn f(re: f64) -> f64 {
        GrafAltinakar::default().friction_factor(re)
    }

    fn log_range(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| lo * (hi / lo).powf(i as f64 / n as f64))
    }

    #[test]
    fn solves_the_graf_altinakar_law() {
        for re in log_range(RE_LAMINAR * 1.000_001, 1e9, 60) {
            let lhs = 1.0 / f(re).sqrt();
            let rhs = 2.0 * (re * f(re).sqrt() / 4.0).log10() + 0.32;
            assert!((lhs - rhs).abs() < 1e-12 * lhs, "Re {re}: 1/sqrt(f) {lhs} against {rhs}");
        }
    }

    #[test]
    fn is_continuous_at_the_laminar_switch() {
        let below = f(RE_LAMINAR);
        let above = f(RE_LAMINAR * (1.0 + 1e-12));
        assert_eq!(below, 48.0 / RE_LAMINAR);
        assert!((above / below - 1.0).abs() < 1e-9, "laminar {below} turbulent {above}");
    }

    /// An independent smooth-wall law: Blasius 0.3164 Re^-1/4, the alternative of the
    /// authors' implementation, valid for 3e3 < Re < 1e5.
    #[test]
    fn agrees_with_blasius_in_its_range() {
        for re in log_range(3e3, 1e5, 20) {
            let blasius = 0.3164 * re.powf(-0.25);
            assert!((f(re) / blasius - 1.0).abs() < 0.07, "Re {re}: f {} against Blasius {blasius}", f(re));
        }
    }

    /// The peer code's iteration, solved here by bisection on its own equation
    /// 1/sqrt(f) = 2 ln(Re sqrt(f)) + 0.32 (the right side rises, the left falls in f).
    #[test]
    fn the_peer_codes_natural_log_law_is_a_sixth_of_it_in_the_frey_range() {
        let peer = |re: f64| {
            let (mut lo, mut hi) = (1e-6f64, 1.0f64);
            for _ in 0..200 {
                let mid = (lo * hi).sqrt();
                if 1.0 / mid.sqrt() > 2.0 * (re * mid.sqrt()).ln() + 0.32 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        for re in log_range(2e3, 8e3, 12) {
            let ratio = peer(re) / f(re);
            assert!((0.16..=0.18).contains(&ratio), "Re {re}: peer {} against {}", peer(re), f(re));
        }
        let scaled = GrafAltinakar { coefficient: 0.17 };
        for re in [1.0, 600.0, 5e3, 1e7] {
            assert_eq!(scaled.friction_factor(re), 0.17 * f(re));
        }
        for bad in [0.0, -1.0, 11.0, f64::NAN] {
            assert_eq!(GrafAltinakar { coefficient: bad }.validate().unwrap_err().key, "coefficient");
        }
    }

    #[test]
    fn the_poiseuille_number_is_finite_at_rest() {
        assert_eq!(GrafAltinakar::default().poiseuille_number(0.0), 48.0);
        assert!(toml::from_str::<GrafAltinakar>("a = 2").is_err());
    }

    proptest! {
        /// f falls with Re from the laminar 48 / Re through the turbulent smooth-wall law,
        /// positive and finite for every Re > 0
        #[test]
        fn decreases_with_the_reynolds_number(lr in -3f64..12.0, dl in 1e-6f64..0.5) {
            let (a, b) = (10f64.powf(lr), 10f64.powf(lr + dl));
            prop_assert!(f(a).is_finite() && f(a) > 0.0);
            prop_assert!(f(b) < f(a), "Re {a}: {} then Re {b}: {}", f(a), f(b));
        }

        /// the Poiseuille number f Re never falls below the laminar 48 and grows without
        /// bound in the turbulent range (the wall stress then grows faster than U)
        #[test]
        fn poiseuille_number_is_at_least_laminar(lr in -3f64..12.0) {
            let re = 10f64.powf(lr);
            let po = GrafAltinakar::default().poiseuille_number(re);
            prop_assert!(po >= 48.0 * (1.0 - 1e-12), "Re {re}: {po}");
        }
    }
}
