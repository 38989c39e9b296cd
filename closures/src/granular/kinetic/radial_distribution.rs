//! Radial distribution function at contact g0(phi) (the `g0` table of
//! `frictional_collisional`). The Carnahan-Starling g0 is
//! [`saltus_core::grain::carnahan_starling`], shared with the solvers and the diagnostics.

use saltus_core::grain::carnahan_starling;
use saltus_core::Params;
use serde::{Deserialize, Serialize};

/// x^(3/2) as x sqrt(x) (NaN for x < 0, as powf): one square root instead of powf's
/// logarithm and exponential, the dearest part of g0, which the Eulerian solver evaluates
/// twice per cell and step.
#[inline]
fn three_halves(x: f64) -> f64 {
    x * x.sqrt()
}

/// Chialvo & Sundaresan (2013) form: CS + a phi^2 / (phi_max - phi)^(3/2).
///
/// * Source: Chassagne et al. 2023 eq 2.23 (a = 0.58) and eq 3.2 (a = a(mu_p)).
/// * `+inf` for phi >= phi_max (the divergence is kept as a value, never NaN).
#[inline]
pub fn chialvo_sundaresan(phi: f64, phi_max: f64, a: f64) -> f64 {
    if phi >= phi_max {
        return f64::INFINITY;
    }
    carnahan_starling(phi) + a * phi * phi / three_halves(phi_max - phi)
}

/// Regressor x = phi^2 / (phi_max - phi)^(3/2) of Chassagne et al. 2023 eq 3.2,
/// g0 = g0_CS + a(mu_p) x: a measured g0 - g0_CS against it gives a(mu_p) (their
/// figure 4b). `+inf` at phi = phi_max, NaN beyond (no packing there to fit).
#[inline]
pub fn friction_regressor(phi: f64, phi_max: f64) -> f64 {
    phi * phi / three_halves(phi_max - phi)
}

/// Chialvo & Sundaresan's form with the exponent of its divergence free:
/// CS + a phi^2 / (phi_max - phi)^n; n = 3/2 is Chassagne et al. 2023 eq 2.23.
///
/// * Source: the shape of Chialvo & Sundaresan (2013) (Chassagne et al. 2023 eq 2.23) with
///   n a shape parameter: the DEM's g0 of eq 3.1 read against eq 3.2's regressor gives an a
///   that grows with phi (Chassagne et al. 2023 figure 4b; our case 14 runs: 1.6-1.8 below
///   phi 0.3, 2.5-3.2 above), which n > 3/2 with a fixed a reproduces.
/// * `+inf` for phi >= phi_max.
#[inline]
pub fn chialvo_sundaresan_power(phi: f64, phi_max: f64, a: f64, n: f64) -> f64 {
    if phi >= phi_max {
        return f64::INFINITY;
    }
    // n = 3/2 is eq 2.23 itself, to the last bit
    let b = phi_max - phi;
    carnahan_starling(phi) + a * phi * phi / if n == 1.5 { three_halves(b) } else { b.powf(n) }
}

/// Torquato (1995) g0: Carnahan-Starling up to the freezing packing phi_f, then
/// g0(phi_f) (phi_c - phi_f) / (phi_c - phi), diverging as 1/(phi_c - phi) at random close
/// packing phi_c (here the closure's phi_max).
///
/// * Source: S. Torquato 1995, "Nearest-neighbor statistics for packings of hard spheres
///   and disks", Phys. Rev. E 51, 3170 (phi_f = 0.49, phi_c = 0.64), the form dense
///   granular kinetic theories take near jamming (e.g. Vescovi et al. 2013, Phys. Fluids
///   25, 063301).
/// * Continuous at phi_f; `+inf` for phi >= phi_max; phi_f >= phi_max is Carnahan-Starling
///   up to phi_max. At or above Carnahan-Starling everywhere for phi_f >= 0.45 (phi_max =
///   0.635), where the pole branch leaves phi_f steeper; below, it dips under it first.
#[inline]
pub fn torquato(phi: f64, phi_max: f64, phi_f: f64) -> f64 {
    if phi >= phi_max {
        return f64::INFINITY;
    }
    if phi <= phi_f {
        return carnahan_starling(phi);
    }
    carnahan_starling(phi_f) * (phi_max - phi_f) / (phi_max - phi)
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

/// Parameters of the `chialvo_sundaresan_power` g0.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct ChialvoSundaresanPowerG0 {
    /// coefficient a of the divergent term a phi^2/(phi_max - phi)^n
    #[param(range = "[0, 100]", unit = "-")]
    pub a: f64,
    /// exponent n of the divergence (3/2: eq 2.23)
    #[param(range = "[0.5, 4]", unit = "-")]
    pub exponent: f64,
}

impl Default for ChialvoSundaresanPowerG0 {
    fn default() -> Self {
        Self { a: 0.58, exponent: 1.5 }
    }
}

/// Parameter of the `torquato` g0.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct TorquatoG0 {
    /// freezing packing where the divergent branch starts
    #[param(range = "[0.3, 0.62]", unit = "-")]
    pub phi_f: f64,
}

impl Default for TorquatoG0 {
    fn default() -> Self {
        Self { phi_f: 0.49 }
    }
}

/// Radial distribution function at contact, chosen by `type`:
///
/// * `{ type = "carnahan_starling" }`: (2 - phi)/(2 (1 - phi)^3); ignores `phi_max`.
/// * `{ type = "chialvo_sundaresan", a = 0.58 }`: eq 2.23 (initial model of Chassagne).
/// * `{ type = "chialvo_sundaresan_friction", a0 = 0.58, a_max = 3.70, delta = 0.54 }`:
///   eq 3.2 with a(mu_p) of eq 3.3 and mu_p the model's `friction` (proposed model).
/// * `{ type = "chialvo_sundaresan_power", a = 0.58, exponent = 1.5 }`: eq 2.23 with the
///   exponent of the divergence free ([`chialvo_sundaresan_power`]).
/// * `{ type = "torquato", phi_f = 0.49 }`: Torquato 1995 ([`torquato`]).
///
/// Every form but Carnahan-Starling returns `+inf` for phi >= phi_max.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum RadialDistribution {
    /// Carnahan & Starling (1969) (an empty struct variant so that unknown keys are refused)
    CarnahanStarling {},
    /// Chialvo & Sundaresan (2013), constant a
    ChialvoSundaresan(ChialvoSundaresanG0),
    /// Chassagne et al. (2023) eqs 3.2-3.3, a depending on interparticle friction
    ChialvoSundaresanFriction(ChialvoSundaresanFrictionG0),
    /// Chialvo & Sundaresan's form with a free exponent
    ChialvoSundaresanPower(ChialvoSundaresanPowerG0),
    /// Torquato (1995)
    Torquato(TorquatoG0),
}

impl Default for RadialDistribution {
    fn default() -> Self {
        Self::ChialvoSundaresanFriction(ChialvoSundaresanFrictionG0::default())
    }
}

impl RadialDistribution {
    /// Coefficient a of the divergent term at interparticle friction `mu_p`, g0 = g0_CS +
    /// a x with x the [`RadialDistribution::regressor`] (0 for Carnahan-Starling, whose regressor is eq 3.2's; 1 for
    /// Torquato's, whose divergent part is the regressor itself).
    pub fn coefficient_a(&self, mu_p: f64) -> f64 {
        match self {
            Self::CarnahanStarling {} => 0.0,
            Self::ChialvoSundaresan(c) => c.a,
            Self::ChialvoSundaresanFriction(c) => friction_coefficient_a(mu_p, c.a0, c.a_max, c.delta),
            Self::ChialvoSundaresanPower(c) => c.a,
            Self::Torquato(_) => 1.0,
        }
    }

    /// The regressor x of g0 = g0_CS + a x: phi^2 / (phi_max - phi)^n of the
    /// Chialvo-Sundaresan forms (n = 3/2 but for the power form, eq 3.2's
    /// [`friction_regressor`]), Torquato's g0 - g0_CS. Carnahan-Starling is eq 3.2 with
    /// a = 0, so its regressor is eq 3.2's: a measured g0 read against it gives the a that
    /// eq 3.2 would need, which a zero regressor would leave undefined.
    pub fn regressor(&self, phi: f64, phi_max: f64) -> f64 {
        match self {
            Self::CarnahanStarling {} | Self::ChialvoSundaresan(_) | Self::ChialvoSundaresanFriction(_) => {
                friction_regressor(phi, phi_max)
            }
            Self::ChialvoSundaresanPower(c) => phi * phi / (phi_max - phi).powf(c.exponent),
            Self::Torquato(c) => torquato(phi, phi_max, c.phi_f) - carnahan_starling(phi),
        }
    }

    /// g0 at `phi` for maximum packing `phi_max` and interparticle friction `mu_p`.
    #[inline]
    pub fn g0(&self, phi: f64, phi_max: f64, mu_p: f64) -> f64 {
        self.g0_with_a(phi, phi_max, self.coefficient_a(mu_p))
    }

    /// g0 at `phi` with the coefficient `a` = [`RadialDistribution::coefficient_a`] given:
    /// a(mu_p) depends on the parameters only, so that a batch over a column computes its
    /// tanh once (the same value bit for bit as [`RadialDistribution::g0`]).
    #[inline]
    pub fn g0_with_a(&self, phi: f64, phi_max: f64, a: f64) -> f64 {
        match self {
            Self::CarnahanStarling {} => carnahan_starling(phi),
            Self::ChialvoSundaresanPower(c) => chialvo_sundaresan_power(phi, phi_max, c.a, c.exponent),
            Self::Torquato(c) => torquato(phi, phi_max, c.phi_f),
            _ => chialvo_sundaresan(phi, phi_max, a),
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

    /// The power form is eq 2.23 at n = 3/2, bit for bit, and diverges faster for a
    /// larger n: near jamming g0 - g0_CS grows as (phi_max - phi)^-n.
    #[test]
    fn the_power_form_is_eq_2_23_at_three_halves_and_its_exponent_sets_the_divergence() {
        for phi in [0.0, 0.1, 0.3, 0.5, 0.62] {
            assert_eq!(chialvo_sundaresan_power(phi, 0.635, 0.58, 1.5), chialvo_sundaresan(phi, 0.635, 0.58));
        }
        let excess = |phi: f64, n: f64| chialvo_sundaresan_power(phi, 0.635, 1.0, n) - carnahan_starling(phi);
        for n in [1.0, 2.0, 3.0] {
            let (e1, e2) = (excess(0.635 - 1e-4, n), excess(0.635 - 1e-5, n));
            let slope = (e2 / e1).log10();
            assert!((slope - n).abs() < 1e-3, "n = {n}: {slope}");
        }
        assert_eq!(chialvo_sundaresan_power(0.635, 0.635, 1.0, 2.0), f64::INFINITY);
        let g = RadialDistribution::ChialvoSundaresanPower(ChialvoSundaresanPowerG0 { a: 2.0, exponent: 2.5 });
        assert_relative_eq!(
            g.g0(0.4, 0.635, 0.0) - carnahan_starling(0.4),
            2.0 * g.regressor(0.4, 0.635),
            max_relative = 1e-14
        );
    }

    /// Torquato 1995: Carnahan-Starling up to phi_f, continuous there, then a simple pole at
    /// phi_max (g0 (phi_max - phi) constant), above Carnahan-Starling's value up to jamming
    /// only where the pole is steeper (close to phi_max).
    #[test]
    fn torquato_is_carnahan_starling_to_freezing_then_a_simple_pole() {
        assert_eq!(torquato(0.3, 0.64, 0.49), carnahan_starling(0.3));
        assert_relative_eq!(torquato(0.49 + 1e-12, 0.64, 0.49), carnahan_starling(0.49), max_relative = 1e-9);
        let c = torquato(0.55, 0.64, 0.49) * (0.64 - 0.55);
        for phi in [0.5, 0.6, 0.63, 0.6399] {
            assert_relative_eq!(torquato(phi, 0.64, 0.49) * (0.64 - phi), c, max_relative = 1e-12);
        }
        assert_eq!(torquato(0.64, 0.64, 0.49), f64::INFINITY);
        assert_relative_eq!(carnahan_starling(0.49), (1.0 - 0.245) / 0.51f64.powi(3), max_relative = 1e-14);
        let g = RadialDistribution::Torquato(TorquatoG0::default());
        assert_eq!(g.g0(0.0, 0.635, 0.4), 1.0);
        assert_eq!(g.regressor(0.3, 0.635), 0.0);
        // Carnahan-Starling reads a measured g0 against eq 3.2's friction term
        let cs = RadialDistribution::CarnahanStarling {};
        assert_eq!(cs.regressor(0.4, 0.635), friction_regressor(0.4, 0.635));
        assert_eq!(cs.coefficient_a(0.4), 0.0);
    }

    proptest! {
        /// Every form of g0 is at least Carnahan-Starling's, increases with phi and is
        /// finite below phi_max.
        #[test]
        fn every_form_increases_and_the_power_form_is_at_least_carnahan_starling(
            phi in 0.0f64..0.63, dphi in 1e-6f64..1e-3, a in 0.0f64..10.0, n in 0.5f64..4.0, phi_f in 0.3f64..0.62
        ) {
            let power = RadialDistribution::ChialvoSundaresanPower(ChialvoSundaresanPowerG0 { a, exponent: n });
            let v = power.g0(phi, 0.635, 0.4);
            prop_assert!(v.is_finite() && v >= carnahan_starling(phi));
            prop_assert!(power.g0(phi + dphi, 0.635, 0.4) > v);
            let torquato = RadialDistribution::Torquato(TorquatoG0 { phi_f });
            let v = torquato.g0(phi, 0.635, 0.4);
            prop_assert!(v.is_finite() && v >= 1.0);
            prop_assert!(torquato.g0(phi + dphi, 0.635, 0.4) > v);
        }

        /// The pole branch starts steeper than Carnahan-Starling (so stays above it up to
        /// jamming) where 1/(phi_max - phi_f) >= d ln g0_CS / d phi at phi_f: phi_f >= 0.45
        /// for phi_max = 0.635. Below, the pole branch falls under Carnahan-Starling first.
        #[test]
        fn torquato_is_at_least_carnahan_starling_from_a_freezing_packing_of_045(
            phi in 0.0f64..0.63, phi_f in 0.45f64..0.62
        ) {
            prop_assert!(torquato(phi, 0.635, phi_f) >= carnahan_starling(phi) * (1.0 - 1e-14));
        }

        #[test]
        fn increasing_and_at_least_carnahan_starling(phi in 0.0f64..0.63, dphi in 1e-6f64..1e-3, mu in 0.0f64..2.0) {
            let g = RadialDistribution::default();
            let a = g.g0(phi, 0.635, mu);
            prop_assert!(a >= carnahan_starling(phi));
            prop_assert!(g.g0(phi + dphi, 0.635, mu) > a);
        }
    }
}
