//! Parabolic eddy viscosity of a uniform open-channel flow, through its mixing length (the
//! Rouse benchmark).

use saltus_core::closure::Family;
use saltus_core::{register_model, ColumnView, Describe, Field, Limit, Needs, Turbulence};
use serde::{Deserialize, Serialize};

/// Parabolic eddy viscosity through its mixing length
///
/// l_m = kappa z sqrt(1 - z/h), nu_t = l_m^2 |du/dz|: in a uniform channel, where the stress
/// u*^2 (1 - z/h) is carried by the eddies (nu_t >> nu), du/dz = u*/(kappa z) and
/// nu_t = kappa u* z (1 - z/h) ([`Parabolic::at`]), the parabola of the Rouse profile.
///
/// * Source: the eddy viscosity of Rouse (1937) behind Cheng, Chauchat, Hsu & Calantoni
///   eq 38 (the Rouse profile) and docs/verification.md, benchmark 3; the product of the linear
///   stress and the log-law shear rate u*/(kappa z).
/// * Defaults: `kappa = 0.41`, `friction_velocity = 0.05`, `depth = 0.1` (the scales of
///   `cases/verification/rouse_parabolic.toml`; a scene of another flow gives its own).
/// * Valid range: `friction_velocity` > 0 (m/s; it enters [`Parabolic::at`], the target
///   parabola, not the mixing length), `depth` > 0 (m) measured from the bottom of the
///   column (z = 0), `kappa` in (0, 1]. The parabola holds where the flow is the uniform
///   channel of that u* and h and nu_t >> nu (z+ >> 10): a verification closure for the
///   Rouse balance (docs/verification.md, benchmark 3), not a model of a developing flow.
///
/// Decisions:
/// * Through the mixing length, not prescribed, so that nu_t = l_m^2 |du/dz| as for every
///   turbulence closure (the point and column forms agree, and nu_t vanishes with the
///   shear). The viscous share lowers nu_t by about nu/2 near the wall: 0.5 % at z+ = 100.
/// * Above z = h (a column taller than `depth`) l_m = 0.
/// * Declared limit: l_m / z = kappa sqrt(1 - z/h) -> `kappa` as z -> 0, the law of the
///   wall of the clear fluid (l_m does not depend on phi).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "parabolic",
    source = "Rouse 1937 (Cheng et al. eq 38); docs/verification.md, benchmark 3",
    equation = "nu_t = l^2 |du/dz|, l = kappa z sqrt(1 - z/h) (kappa u* z (1 - z/h) in a uniform channel)",
    limits = [Limit::WallLength { kappa: self.kappa }]
)]
pub struct Parabolic {
    /// friction velocity u*
    #[param(range = "(0, inf)", unit = "m/s")]
    pub friction_velocity: f64,
    /// depth h over which the parabola spans, from z = 0
    #[param(range = "(0, inf)", unit = "m")]
    pub depth: f64,
    /// von Karman constant
    #[param(range = "(0, 1]", unit = "-")]
    pub kappa: f64,
}

impl Default for Parabolic {
    fn default() -> Self {
        Self { friction_velocity: 0.05, depth: 0.1, kappa: 0.41 }
    }
}

impl Parabolic {
    /// The parabola kappa u* z (1 - z/h) at height `z` (m^2/s), the nu_t of the uniform
    /// channel.
    #[inline]
    pub fn at(&self, z: f64) -> f64 {
        let x = z / self.depth;
        if x > 0.0 && x < 1.0 {
            self.kappa * self.friction_velocity * z * (1.0 - x)
        } else {
            0.0
        }
    }
}

#[typetag::serde(name = "parabolic")]
impl Turbulence for Parabolic {
    fn provides(&self) -> Needs {
        Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress])
    }

    fn mixing_length(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        for (o, &z) in out.iter_mut().zip(col.z) {
            *o = self.kappa * z * (1.0 - z / self.depth).clamp(0.0, 1.0).sqrt();
        }
    }
}

register_model!(Family::Turbulence, "parabolic", Turbulence, Parabolic);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn model() -> Parabolic {
        Parabolic { friction_velocity: 0.03, depth: 0.1, ..Parabolic::default() }
    }

    #[test]
    fn parabola_peaks_at_half_depth_and_vanishes_at_both_ends() {
        let m = model();
        // maximum kappa u* h / 4 at z = h/2
        assert_relative_eq!(m.at(0.05), 0.41 * 0.03 * 0.1 / 4.0, max_relative = 1e-15);
        assert_eq!(m.at(0.0), 0.0);
        assert_eq!(m.at(0.1), 0.0);
        assert_eq!(m.at(0.2), 0.0);
        assert_eq!(m.at(-0.01), 0.0);
    }

    #[test]
    fn the_mixing_length_gives_the_parabola_with_the_log_law_shear() {
        // l^2 u*/(kappa z) = kappa u* z (1 - z/h)
        let m = model();
        let z = [0.01, 0.03, 0.07];
        let dz = [0.02; 3];
        let phi = [0.0; 3];
        let dudz: Vec<f64> = z.iter().map(|z| 0.03 / (0.41 * z)).collect();
        let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 1e-4, nu_f: 1e-6, transported: &[] };
        let mut l = [0.0; 3];
        m.mixing_length(&col, &mut l);
        let mut nu = [0.0; 3];
        m.eddy_viscosity(&col, &mut nu);
        for i in 0..3 {
            assert_relative_eq!(nu[i], m.at(z[i]), max_relative = 1e-12);
        }
    }

    #[test]
    fn validate_refuses_missing_scales() {
        assert_eq!(Parabolic { friction_velocity: 0.0, ..model() }.validate().unwrap_err().key, "friction_velocity");
        assert_eq!(Parabolic { depth: 0.0, ..model() }.validate().unwrap_err().key, "depth");
        assert!(model().validate().is_ok());
    }

    proptest! {
        #[test]
        fn non_negative_and_symmetric_about_half_depth(x in 0.0f64..1.0) {
            let m = model();
            let a = m.at(x * 0.1);
            prop_assert!(a >= 0.0 && a.is_finite());
            prop_assert!((a - m.at((1.0 - x) * 0.1)).abs() <= 1e-15);
        }
    }
}
