//! Richardson-Zaki hindrance.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragReynolds, Hindrance, Limit};
use serde::{Deserialize, Serialize};

/// Richardson & Zaki (1954) hindrance of the drag force
///
/// f(phi) = (1 - phi)^(-zeta)
///
/// * Source: Maurin et al. 2015 eq 12 (C_D = (0.4 + 24.4/Re_p)(1-phi)^(-zeta)); Chassagne
///   et al. 2023 eq 2.10, whose drag coefficient K contains (1-phi)^(-zeta-1) and whose
///   momentum exchange n f_D = phi (1-phi) K u_r (eq 2.26: (3 rho_f/4d) phi (1-phi)^(-zeta)
///   C_D |u_r| u_r), so that the force on one particle is the single-particle force times
///   (1-phi)^(-zeta); after Richardson & Zaki 1954, Trans. Instn Chem. Engrs 32, 35-53.
/// * Defaults: `exponent` zeta = 3.1 (Jenkins & Hanes 1998, as both papers).
/// * Valid range: `exponent` in [0, 10]; phi in [0, 1) (diverges as phi -> 1); C_D is
///   evaluated at the interstitial Re_p (the papers' convention). With the suspension's
///   buoyancy, the hindered slip then solves (3/4) C_D(Re) u_r^2 = (s-1) g d (1-phi)^(1+zeta)
///   (docs/verification.md, benchmark 5).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "richardson_zaki",
    source = "Maurin et al. 2015 eq 12; Chassagne et al. 2023 eqs 2.10, 2.26; Richardson & Zaki 1954",
    equation = "f = (1 - phi)^(-exponent)",
    limits = [Limit::Dilute, Limit::Increasing]
)]
pub struct RichardsonZaki {
    /// Richardson-Zaki exponent zeta of the drag-force factor (1-phi)^(-zeta)
    #[param(range = "[0, 10]", unit = "-")]
    pub exponent: f64,
}

impl Default for RichardsonZaki {
    fn default() -> Self {
        Self { exponent: 3.1 }
    }
}

#[typetag::serde(name = "richardson_zaki")]
impl Hindrance for RichardsonZaki {
    #[inline]
    fn factor(&self, phi: f64, _re_p: f64) -> f64 {
        (1.0 - phi).powf(-self.exponent)
    }
    fn reynolds_convention(&self) -> DragReynolds {
        DragReynolds::Interstitial
    }
    fn depends_on_reynolds(&self) -> bool {
        false
    }
}

register_model!(Family::Hindrance, "richardson_zaki", Hindrance, RichardsonZaki);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn values() {
        let h = RichardsonZaki::default();
        assert_eq!(h.factor(0.0, 10.0), 1.0);
        assert_relative_eq!(h.factor(0.5, 10.0), 2f64.powf(3.1), max_relative = 1e-15);
        assert_relative_eq!(h.factor(0.3, 0.0), 0.7f64.powf(-3.1), max_relative = 1e-15);
        assert_eq!(h.drag_reynolds(0.3, 7.0), 7.0);
        assert_eq!(RichardsonZaki { exponent: 0.0 }.factor(0.6, 1.0), 1.0);
    }

    #[test]
    fn validate_refuses_out_of_range_exponent() {
        for bad in [-0.1, 10.5, f64::NAN, f64::INFINITY] {
            let e = RichardsonZaki { exponent: bad }.validate().unwrap_err();
            assert_eq!(e.key, "exponent");
        }
        assert!(RichardsonZaki::default().validate().is_ok());
    }

    #[test]
    fn parses_from_toml() {
        let h: RichardsonZaki = toml::from_str("exponent = 4.65").unwrap();
        assert_eq!(h.exponent, 4.65);
        assert_eq!(toml::from_str::<RichardsonZaki>("").unwrap(), RichardsonZaki::default());
        assert!(toml::from_str::<RichardsonZaki>("zeta = 3.1").is_err());
    }

    proptest! {
        #[test]
        fn tends_to_one_as_phi_vanishes(phi in 0f64..1e-7, re in 0f64..1e5, n in 0f64..=10.0) {
            let f = RichardsonZaki { exponent: n }.factor(phi, re);
            prop_assert!((f - 1.0).abs() <= 1.01 * n * phi + 1e-15);
        }

        #[test]
        fn at_least_one_and_increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04, re in 0f64..1e4, n in 0.1f64..=10.0) {
            let h = RichardsonZaki { exponent: n };
            prop_assert!(h.factor(phi, re) >= 1.0);
            prop_assert!(h.factor(phi + dphi, re) > h.factor(phi, re));
        }
    }
}
