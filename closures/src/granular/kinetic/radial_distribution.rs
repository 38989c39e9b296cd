//! Radial distribution function at contact g0(phi) (the `g0` table of
//! `frictional_collisional`). The Carnahan-Starling g0 is
//! [`saltus_core::grain::carnahan_starling`], shared with the solvers and the diagnostics.

use saltus_core::grain::carnahan_starling;
use saltus_core::Params;
use serde::{Deserialize, Serialize};

/// Chialvo & Sundaresan (2013) form: CS + a phi^2 / (phi_max - phi)^(3/2).
///
/// * Source: Chassagne et al. 2023 eq 2.23 (a = 0.58) and eq 3.2 (a = a(mu_p)).
/// * `+inf` for phi >= phi_max (the divergence is kept as a value, never NaN).
#[inline]
pub fn chialvo_sundaresan(phi: f64, phi_max: f64, a: f64) -> f64 {
    if phi >= phi_max {
        return f64::INFINITY;
    }
    carnahan_starling(phi) + a * phi * phi / (phi_max - phi).powf(1.5)
}

/// Regressor x = phi^2 / (phi_max - phi)^(3/2) of Chassagne et al. 2023 eq 3.2,
/// g0 = g0_CS + a(mu_p) x: a measured g0 - g0_CS against it gives a(mu_p) (their
/// figure 4b). `+inf` at phi = phi_max, NaN beyond (no packing there to fit).
#[inline]
pub fn friction_regressor(phi: f64, phi_max: f64) -> f64 {
    phi * phi / (phi_max - phi).powf(1.5)
}

/// Friction-dependent coefficient a(mu_p) = a0 + (a_max - a0) tanh(mu_p / delta),
/// Chassagne et al. 2023 eq 3.3.
#[inline]
pub fn friction_coefficient_a(mu_p: f64, a0: f64, a_max: f64, delta: f64) -> f64 {
    a0 + (a_max - a0) * (mu_p / delta).tanh()
}

/// Parameter of the `chialvo_sundaresan` g0.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct ChialvoSundaresanG0 {
    /// coefficient a of the divergent term a phi^2/(phi_max - phi)^1.5
    #[param(range = "[0, 100]", unit = "-")]
    pub a: f64,
}

impl Default for ChialvoSundaresanG0 {
    fn default() -> Self {
        Self { a: 0.58 }
    }
}

/// Parameters of the `chialvo_sundaresan_friction` g0.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct ChialvoSundaresanFrictionG0 {
    /// a at mu_p = 0
    #[param(range = "[0, 100]", unit = "-")]
    pub a0: f64,
    /// a at large mu_p
    #[param(range = "[0, 100]", unit = "-")]
    pub a_max: f64,
    /// friction scale of tanh(mu_p/delta)
    #[param(range = "(0, inf)", unit = "-")]
    pub delta: f64,
}

impl Default for ChialvoSundaresanFrictionG0 {
    fn default() -> Self {
        Self { a0: 0.58, a_max: 3.70, delta: 0.54 }
    }
}

/// Radial distribution function at contact, chosen by `type`:
///
/// * `{ type = "carnahan_starling" }`: (2 - phi)/(2 (1 - phi)^3); ignores `phi_max`.
/// * `{ type = "chialvo_sundaresan", a = 0.58 }`: eq 2.23 (initial model of Chassagne).
/// * `{ type = "chialvo_sundaresan_friction", a0 = 0.58, a_max = 3.70, delta = 0.54 }`:
///   eq 3.2 with a(mu_p) of eq 3.3 and mu_p the model's `friction` (proposed model).
///
/// The two Chialvo-Sundaresan forms return `+inf` for phi >= phi_max.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum RadialDistribution {
    /// Carnahan & Starling (1969) (an empty struct variant so that unknown keys are refused)
    CarnahanStarling {},
    /// Chialvo & Sundaresan (2013), constant a
    ChialvoSundaresan(ChialvoSundaresanG0),
    /// Chassagne et al. (2023) eqs 3.2-3.3, a depending on interparticle friction
    ChialvoSundaresanFriction(ChialvoSundaresanFrictionG0),
}

impl Default for RadialDistribution {
    fn default() -> Self {
        Self::ChialvoSundaresanFriction(ChialvoSundaresanFrictionG0::default())
    }
}

impl RadialDistribution {
    /// Coefficient a of the divergent term at interparticle friction `mu_p` (0 for
    /// Carnahan-Starling).
    pub fn coefficient_a(&self, mu_p: f64) -> f64 {
        match self {
            Self::CarnahanStarling {} => 0.0,
            Self::ChialvoSundaresan(c) => c.a,
            Self::ChialvoSundaresanFriction(c) => friction_coefficient_a(mu_p, c.a0, c.a_max, c.delta),
        }
    }

    /// g0 at `phi` for maximum packing `phi_max` and interparticle friction `mu_p`.
    #[inline]
    pub fn g0(&self, phi: f64, phi_max: f64, mu_p: f64) -> f64 {
        match self {
            Self::CarnahanStarling {} => carnahan_starling(phi),
            _ => chialvo_sundaresan(phi, phi_max, self.coefficient_a(mu_p)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn g0_of_zero_is_one() {
        assert_eq!(carnahan_starling(0.0), 1.0);
        for g in [
            RadialDistribution::CarnahanStarling {},
            RadialDistribution::ChialvoSundaresan(ChialvoSundaresanG0::default()),
            RadialDistribution::default(),
        ] {
            assert_eq!(g.g0(0.0, 0.635, 0.4), 1.0);
        }
    }

    #[test]
    fn chialvo_sundaresan_tends_to_carnahan_starling_as_phi_vanishes() {
        let g = RadialDistribution::default();
        let mut last = f64::INFINITY;
        for k in 1..8 {
            let phi = 10f64.powi(-k);
            let rel = (g.g0(phi, 0.635, 0.4) - carnahan_starling(phi)) / carnahan_starling(phi);
            assert!(rel >= 0.0 && rel < last, "phi = {phi}: {rel}");
            last = rel;
        }
        assert!(last < 1e-12);
    }

    #[test]
    fn chialvo_sundaresan_diverges_at_phi_max() {
        let g = RadialDistribution::ChialvoSundaresan(ChialvoSundaresanG0::default());
        let mut last = 0.0;
        for k in 1..10 {
            let phi = 0.635 - 10f64.powi(-k);
            let v = g.g0(phi, 0.635, 0.0);
            assert!(v.is_finite() && v > last);
            last = v;
        }
        assert!(last > 1e12);
        assert_eq!(g.g0(0.635, 0.635, 0.0), f64::INFINITY);
        assert_eq!(g.g0(0.9, 0.635, 0.0), f64::INFINITY);
        assert_eq!(carnahan_starling(1.0), f64::INFINITY);
    }

    #[test]
    fn friction_coefficient_of_the_paper() {
        let g = RadialDistribution::default();
        assert_eq!(g.coefficient_a(0.0), 0.58);
        assert_relative_eq!(g.coefficient_a(0.4), 0.58 + 3.12 * (0.4f64 / 0.54).tanh(), max_relative = 1e-15);
        assert_relative_eq!(g.coefficient_a(50.0), 3.70, max_relative = 1e-12);
    }

    proptest! {
        #[test]
        fn increasing_and_at_least_carnahan_starling(phi in 0.0f64..0.63, dphi in 1e-6f64..1e-3, mu in 0.0f64..2.0) {
            let g = RadialDistribution::default();
            let a = g.g0(phi, 0.635, mu);
            prop_assert!(a >= carnahan_starling(phi));
            prop_assert!(g.g0(phi + dphi, 0.635, mu) > a);
        }
    }
}
