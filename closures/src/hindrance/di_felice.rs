//! Di Felice hindrance with a Reynolds-dependent exponent.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragReynolds, Hindrance, Limit, Params};
use serde::{Deserialize, Serialize};

/// Which Reynolds number the Di Felice exponent and the single-particle C_D use.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum ReynoldsConvention {
    /// Re_sup = (1 - phi) |u_f - v_p| d / nu_f (Cheng et al.; peer codes)
    #[default]
    Superficial,
    /// Re_p = |u_f - v_p| d / nu_f
    Interstitial,
}

/// Limit of the exponent n as Re_p -> 0 or Re_p -> inf.
pub const N_LIMIT: f64 = 3.7;

/// Di Felice (1994) hindrance ("voidage function")
///
/// f(phi, Re) = (1 - phi)^(2 - n),  n = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2)
///
/// * Source: Cheng, Chauchat, Hsu & Calantoni eqs 12-13, after Di Felice 1994, Int. J.
///   Multiphase Flow 20, 153-159.
/// * Derivation of the factor: Di Felice writes the force on a particle as
///   F = F0 eps^(-chi) with eps = 1 - phi and F0 the single-particle drag at the
///   *superficial* velocity U = eps u_r, F0 = (1/2) rho_f A C_D(Re_sup) U^2. In terms of the
///   interstitial velocity u_r this is (1/2) rho_f A C_D(Re_sup) u_r^2 eps^(2-chi), i.e.
///   Cheng's eqs 6-7 with f = eps^(2-n). So `factor` = (1 - phi)^(2-n) multiplies the
///   single-particle force at the interstitial relative velocity, with C_D evaluated at
///   [`Hindrance::drag_reynolds`].
/// * Defaults: `reynolds = "superficial"`: both n and C_D use Re_sup = (1 - phi) Re_p, as
///   Cheng defines Re_p (text after eq 7 and after eq 23) and as peer codes do, so
///   `drag_reynolds` returns (1 - phi) Re_p. `reynolds = "interstitial"` uses the
///   interstitial Re_p for both.
/// * Valid range: phi in [0, 1), Re >= 0; n lies in [3.05, 3.7] with its minimum at
///   Re = 10^1.5. At Re = 0 (log10 Re = -inf) n takes its limit 3.7 (no NaN).
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "di_felice",
    source = "Cheng, Chauchat, Hsu & Calantoni eqs 12-13; Di Felice 1994, Int. J. Multiphase Flow 20, 153-159",
    equation = "f = (1 - phi)^(2 - n), n = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2)",
    limits = [Limit::Dilute]
)]
pub struct DiFelice {
    /// Reynolds-number convention of the exponent and of the single-particle C_D
    pub reynolds: ReynoldsConvention,
}

impl DiFelice {
    /// Exponent n(Re) of eq 13; 3.7 for Re <= 0 (the Re -> 0 limit).
    #[inline]
    pub fn exponent(re: f64) -> f64 {
        if re <= 0.0 {
            return N_LIMIT;
        }
        let x = 1.5 - re.log10();
        N_LIMIT - 0.65 * (-0.5 * x * x).exp()
    }

    /// Reynolds number of the convention from the interstitial `re_p`.
    #[inline]
    fn convention_re(&self, phi: f64, re_p: f64) -> f64 {
        self.reynolds_convention().of(phi, re_p)
    }
}

#[typetag::serde(name = "di_felice")]
impl Hindrance for DiFelice {
    #[inline]
    fn factor(&self, phi: f64, re_p: f64) -> f64 {
        let n = Self::exponent(self.convention_re(phi, re_p));
        (1.0 - phi).powf(2.0 - n)
    }
    fn reynolds_convention(&self) -> DragReynolds {
        match self.reynolds {
            ReynoldsConvention::Superficial => DragReynolds::Superficial,
            ReynoldsConvention::Interstitial => DragReynolds::Interstitial,
        }
    }
    fn depends_on_reynolds(&self) -> bool {
        true
    }
}

register_model!(Family::Hindrance, "di_felice", Hindrance, DiFelice);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const INTERSTITIAL: DiFelice = DiFelice { reynolds: ReynoldsConvention::Interstitial };

    #[test]
    fn exponent_values() {
        assert_eq!(DiFelice::exponent(0.0), 3.7);
        assert_eq!(DiFelice::exponent(-1.0), 3.7);
        assert_relative_eq!(DiFelice::exponent(10f64.powf(1.5)), 3.05, max_relative = 1e-14);
        // log10 Re = 0.5: n = 3.7 - 0.65 exp(-1/2)
        assert_relative_eq!(DiFelice::exponent(10f64.sqrt()), 3.7 - 0.65 * (-0.5f64).exp(), max_relative = 1e-14);
        assert!(DiFelice::exponent(1e-300) > 3.69);
        assert!(DiFelice::exponent(1e300) > 3.69);
    }

    #[test]
    fn zero_reynolds_gives_no_nan() {
        let h = DiFelice::default();
        assert_relative_eq!(h.factor(0.4, 0.0), 0.6f64.powf(-1.7), max_relative = 1e-15);
        assert_relative_eq!(INTERSTITIAL.factor(0.4, 0.0), 0.6f64.powf(-1.7), max_relative = 1e-15);
        assert_eq!(h.drag_reynolds(0.4, 0.0), 0.0);
    }

    #[test]
    fn conventions() {
        let sup = DiFelice::default();
        assert_eq!(sup.reynolds, ReynoldsConvention::Superficial);
        assert_relative_eq!(sup.drag_reynolds(0.4, 50.0), 30.0, max_relative = 1e-15);
        assert_eq!(INTERSTITIAL.drag_reynolds(0.4, 50.0), 50.0);
        // superficial Re = 0.6 * 50 = 30 ~ 10^1.477
        let n = DiFelice::exponent(30.0);
        assert_relative_eq!(sup.factor(0.4, 50.0), 0.6f64.powf(2.0 - n), max_relative = 1e-15);
        let n = DiFelice::exponent(50.0);
        assert_relative_eq!(INTERSTITIAL.factor(0.4, 50.0), 0.6f64.powf(2.0 - n), max_relative = 1e-15);
    }

    #[test]
    fn parses_from_toml() {
        let h: DiFelice = toml::from_str("reynolds = \"interstitial\"").unwrap();
        assert_eq!(h, INTERSTITIAL);
        assert_eq!(toml::from_str::<DiFelice>("").unwrap(), DiFelice::default());
        assert!(toml::from_str::<DiFelice>("reynolds = \"mixture\"").is_err());
        assert!(toml::from_str::<DiFelice>("n = 3.7").is_err());
        assert!(DiFelice::default().params().is_empty());
        assert!(INTERSTITIAL.validate().is_ok());
    }

    proptest! {
        #[test]
        fn exponent_in_range_with_minimum_at_10_pow_1_5(lre in -10f64..10.0) {
            let n = DiFelice::exponent(10f64.powf(lre));
            prop_assert!((3.05..=3.7).contains(&n));
            prop_assert!(n >= DiFelice::exponent(10f64.powf(1.5)));
        }

        #[test]
        fn tends_to_one_as_phi_vanishes(phi in 0f64..1e-7, re in 0f64..1e5) {
            for h in [DiFelice::default(), INTERSTITIAL] {
                prop_assert_eq!(h.factor(0.0, re), 1.0);
                prop_assert!((h.factor(phi, re) - 1.0).abs() <= 1.71 * phi + 1e-15);
            }
        }

        #[test]
        fn at_least_one_and_increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04, re in 0f64..1e5) {
            for h in [DiFelice::default(), INTERSTITIAL] {
                prop_assert!(h.factor(phi, re) >= 1.0);
                prop_assert!(h.factor(phi + dphi, re) > h.factor(phi, re));
            }
        }
    }
}
