//! Drag dissipation factor c_J of J_int = -phi (1 - phi) K c_J T.

use saltus_core::Params;
use serde::{Deserialize, Serialize};

/// How the work of the drag force on the velocity fluctuations is closed.
///
/// * `"linear"`: c_J = 3, linear drag (Ding & Gidaspow 1990), Chassagne et al. 2023
///   eq 2.25.
/// * `"quadratic"`: c_J = 3 + 2 C_D^inf / C_D, first-order expansion of a Dallavalle-type
///   quadratic drag with <v_x'^2> ~ 2T, Chassagne et al. 2023 eq 3.13 / App. D eq D11.
///
/// Guard: with C_D <= 0 or not finite the ratio C_D^inf / C_D is taken as 1 (fully
/// quadratic limit); C_D = +inf (Re_p -> 0) gives 3. No clamp otherwise.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum DragDissipation {
    /// c_J = 3 (eq 2.25)
    Linear,
    /// c_J = 3 + 2 C_D^inf / C_D (eq 3.13)
    #[default]
    Quadratic,
}

impl DragDissipation {
    /// c_J for single-particle drag coefficient `cd` and its high-Re limit `cd_inf`.
    #[inline]
    pub fn factor(self, cd_inf: f64, cd: f64) -> f64 {
        match self {
            Self::Linear => 3.0,
            Self::Quadratic => {
                let ratio = if cd.is_nan() || cd <= 0.0 {
                    1.0
                } else if cd.is_infinite() {
                    0.0
                } else {
                    cd_inf / cd
                };
                3.0 + 2.0 * ratio
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors() {
        assert_eq!(DragDissipation::Linear.factor(0.4, 1.0), 3.0);
        assert_eq!(DragDissipation::Quadratic.factor(0.4, 0.4), 5.0);
        assert_eq!(DragDissipation::Quadratic.factor(0.4, 0.8), 4.0);
        assert_eq!(DragDissipation::Quadratic.factor(0.4, f64::INFINITY), 3.0);
        assert_eq!(DragDissipation::Quadratic.factor(0.4, 0.0), 5.0);
        // Dallavalle at Re_p = 100: C_D = 0.4 + 0.244
        let cd = 0.4 + 24.4 / 100.0;
        assert!((DragDissipation::Quadratic.factor(0.4, cd) - (3.0 + 0.8 / cd)).abs() < 1e-15);
    }
}
