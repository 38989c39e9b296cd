//! Frictionless walls.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, WallFriction};
use serde::{Deserialize, Serialize};

/// Frictionless side walls: the fluid does not feel them
///
/// f = 0
///
/// * Source: the limit W -> infinity of the side-wall correction of Maurin et al. 2015
///   section III B (the column without walls), kept as a model so that a scene with
///   `[closures.wall_friction]` can be run without the correction by `--set
///   closures.wall_friction.type=none`.
/// * Defaults: no parameters.
/// * Valid range: any Re >= 0.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(name = "none", source = "the wide-channel limit of Maurin et al. 2015 section III B", equation = "f = 0")]
pub struct NoWallFriction {}

#[typetag::serde(name = "none")]
impl WallFriction for NoWallFriction {
    fn poiseuille_number(&self, _re: f64) -> f64 {
        0.0
    }
    /// 0 at every Re, Re = 0 included (the default quotient f Re / Re would be 0 / 0 there)
    fn friction_factor(&self, _re: f64) -> f64 {
        0.0
    }
}

register_model!(Family::WallFriction, "none", WallFriction, NoWallFriction);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn is_zero_at_every_reynolds_number(lr in -6f64..12.0) {
            prop_assert_eq!(NoWallFriction::default().friction_factor(0.0), 0.0);
            let re = 10f64.powf(lr);
            prop_assert_eq!(NoWallFriction::default().poiseuille_number(re), 0.0);
            prop_assert_eq!(NoWallFriction::default().friction_factor(re), 0.0);
        }
    }
}
