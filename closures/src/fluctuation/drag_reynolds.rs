//! The drag's particle Reynolds number under a fluctuation closure's draws (key
//! `drag_reynolds` of `eim`).

use saltus_core::{Params, SlipReynolds};
use serde::{Deserialize, Serialize};

/// Which slip the drag's particle Reynolds number takes when the grain sees a fluctuation
/// u' (key `drag_reynolds` of `eim`)
///
/// ```text
/// F_D = (1/2) rho_f C_D(Re_p) f(phi, Re_p) (pi d^2 / 4) |u_r| u_r,   u_r = u_f + u' - v
/// instantaneous:  Re_p = |u_f + u' - v| d / nu_f
/// mean:           Re_p = |u_f - v| d / nu_f
/// ```
///
/// * Source: Cheng, Chauchat, Hsu & Calantoni, eqs 6-7 and 12-13: the force of eq 6 takes
///   the instantaneous slip u_f + u' - v (section 2.1: "the instantaneous fluid velocity is
///   decomposed into the Reynolds-averaged component and the turbulent fluctuating
///   component"), the drag coefficient of eq 7 and the hindrance exponent of eq 13 the
///   particle Reynolds number Re_p = (1 - phi) |u_f - v| d / nu_f of the Reynolds-averaged
///   fluid velocity (the (1 - phi) is the hindrance's own Reynolds convention,
///   `closures.hindrance`).
/// * Default: `instantaneous` (the drag of every scene written before this key).
/// * Valid values: `instantaneous`, `mean`. Acts where the draws act (the DEM's grains);
///   the mean-field face has no u' and is the same under both.
///
/// Limits: with u' = 0 both give |u_f - v|; under `mean` Re_p does not depend on u', so
/// C_D and f are those of the mean slip whatever the draw (the force stays eq 6's
/// |u_r| u_r times them); under `instantaneous` Re_p differs from the mean one by at most
/// |u'| d / nu_f (the triangle inequality).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum DragReynoldsNumber {
    /// Re_p of the instantaneous slip |u_f + u' - v|
    #[default]
    Instantaneous,
    /// Re_p of the mean slip |u_f - v| (Cheng eq 7)
    Mean,
}

impl DragReynoldsNumber {
    /// The solver's form of this choice.
    pub fn form(self) -> SlipReynolds {
        match self {
            Self::Instantaneous => SlipReynolds::Instantaneous,
            Self::Mean => SlipReynolds::Mean,
        }
    }

    /// The default (not written in a resolved scene).
    pub fn is_instantaneous(&self) -> bool {
        *self == Self::Instantaneous
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn v3() -> impl Strategy<Value = [f64; 3]> {
        [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0]
    }

    fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }

    fn norm(a: [f64; 3]) -> f64 {
        (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
    }

    proptest! {
        #[test]
        fn without_a_fluctuation_both_forms_take_the_mean_slip(m in v3()) {
            // u' = 0: the instantaneous and the mean slip are one number, |u_f - v|
            for f in [DragReynoldsNumber::Instantaneous, DragReynoldsNumber::Mean] {
                prop_assert_eq!(f.form().slip(m, [0.0; 3]), norm(m));
            }
        }

        #[test]
        fn the_mean_form_does_not_see_the_fluctuation(m in v3(), a in v3(), b in v3()) {
            // two draws u' = a, b on the same mean slip m: eq 7's Re_p is the same
            // (to the rounding of m + u' - u')
            let f = DragReynoldsNumber::Mean.form();
            let (sa, sb) = (f.slip(add(m, a), a), f.slip(add(m, b), b));
            prop_assert!((sa - norm(m)).abs() <= 1e-14 * (1.0 + norm(a)) && (sb - norm(m)).abs() <= 1e-14 * (1.0 + norm(b)));
        }

        #[test]
        fn the_two_forms_differ_by_at_most_the_fluctuation(m in v3(), a in v3()) {
            // | |m + u'| - |m| | <= |u'|, with equality when u' is parallel to m
            let ur = add(m, a);
            let (i, e) = (DragReynoldsNumber::Instantaneous.form().slip(ur, a), DragReynoldsNumber::Mean.form().slip(ur, a));
            prop_assert!((i - e).abs() <= norm(a) * (1.0 + 1e-12) + 1e-14);
            prop_assert_eq!(i, norm(ur));
        }
    }

    #[test]
    fn a_fluctuation_along_the_slip_adds_its_size_to_the_instantaneous_form() {
        // m = (0.3, 0, 0), u' = (0.1, 0, 0): 0.4 against eq 7's 0.3
        let (m, a) = ([0.3, 0.0, 0.0], [0.1, 0.0, 0.0]);
        let ur = add(m, a);
        assert!((DragReynoldsNumber::Instantaneous.form().slip(ur, a) - 0.4).abs() < 1e-15);
        assert!((DragReynoldsNumber::Mean.form().slip(ur, a) - 0.3).abs() < 1e-15);
    }
}
