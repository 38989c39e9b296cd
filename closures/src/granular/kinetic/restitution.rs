//! Effective restitution coefficient used in the collisional dissipation F4 (the
//! `restitution_model` table of `frictional_collisional`).

use saltus_core::Params;
use serde::{Deserialize, Serialize};

/// Jenkins & Zhang (2002) friction correction f(mu_p) of e_eff = e - f(mu_p),
/// Chassagne et al. 2023 App. C eqs C1-C6, with the CORRECTED sliding threshold
/// mu0 = (7/2) mu_p (1+e)/(1+e_t) (the printed eq C6 has (1+e_t)/(1+e_t), a typo; see
/// docs/verification.md):
///
/// ```text
/// f  = (a1 - a2 b1/b2) / 2
/// a1 = (mu_p/mu0) [pi mu0 (1 - 2/pi atan mu0) + 2 mu0^2/(1+mu0^2) (1 - 2 mu_p/mu0)]
/// a2 = 5/2 (mu_p/mu0) [pi/2 mu0 (1 - 2/pi atan mu0) + (mu0^2 - mu0^4)/(1+mu0^2)^2]
/// b1 = (mu_p/mu0)^2 mu0^2/(1+mu0^2)
/// b2 = 1/2 (mu_p/mu0) [pi/2 mu0 (1 - 2/pi atan mu0) + mu0^2/(1+mu0^2)]
/// ```
///
/// Evaluated with r = mu_p/mu0 = (1+e_t)/(7/2 (1+e)) (independent of mu_p) and
/// b1/b2 = 2 r mu0/(1+mu0^2) / [pi/2 (1 - 2/pi atan mu0) + mu0/(1+mu0^2)], so mu_p = 0 gives
/// f = 0 exactly with no 0/0. Small-mu_p expansion: f = pi mu_p/2 - 9/2 mu_p^2 + O(mu_p^4)
/// for EVERY e and e_t (e and e_t enter through mu0 only from the mu_p^4 term on).
/// Large mu_p: f -> 2 r (1 - r). `mu_p < 0` is treated as 0.
pub fn jenkins_zhang_f(mu_p: f64, e: f64, e_t: f64) -> f64 {
    if mu_p.is_nan() || mu_p <= 0.0 {
        return 0.0;
    }
    let pi = std::f64::consts::PI;
    let r = (1.0 + e_t) / (3.5 * (1.0 + e));
    let mu0 = mu_p / r;
    let m2 = mu0 * mu0;
    // pi/2 mu0 (1 - 2/pi atan mu0) = mu0 (pi/2 - atan mu0) = mu0 atan(1/mu0) for mu0 > 0
    let h = 0.5 * pi - mu0.atan();
    let a1 = r * (2.0 * mu0 * h + 2.0 * m2 / (1.0 + m2) * (1.0 - 2.0 * r));
    let a2 = 2.5 * r * (mu0 * h + (m2 - m2 * m2) / ((1.0 + m2) * (1.0 + m2)));
    let b1_over_b2 = 2.0 * r * mu0 / (1.0 + m2) / (h + mu0 / (1.0 + m2));
    0.5 * (a1 - a2 * b1_over_b2)
}

/// Parameters of the `jenkins_zhang` restitution model.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct JenkinsZhang {
    /// tangential restitution of sticking contacts
    #[param(range = "[0, 1]", unit = "-")]
    pub e_t: f64,
}

/// Effective restitution e_eff used in F4 only (F4' = 12/sqrt(pi) (1-e_eff^2) phi^2 g0 =
/// F4 (1-e_eff^2)/(1-e^2)); viscosity and conductivity keep the bare e.
///
/// * `{ type = "plain" }`: e_eff = e (initial model).
/// * `{ type = "jenkins_zhang", e_t = 0 }`: e_eff = max(e - f(mu_p), 0), eq C1 (proposed
///   model). The clamp at 0 is a saltus decision: for small e and large mu_p eq C1 goes
///   negative (e = 0.3, mu_p > ~0.58; e = 0.1, mu_p > ~0.08), where 1 - e_eff^2 would start
///   to *decrease* with friction; clamping keeps dissipation monotone in mu_p.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum RestitutionModel {
    /// e_eff = e (an empty struct variant so that unknown keys are refused)
    Plain {},
    /// e_eff = e - f(mu_p) (Jenkins & Zhang 2002)
    JenkinsZhang(JenkinsZhang),
}

impl Default for RestitutionModel {
    fn default() -> Self {
        Self::JenkinsZhang(JenkinsZhang::default())
    }
}

impl RestitutionModel {
    /// Effective restitution for normal restitution `e` and interparticle friction `mu_p`.
    #[inline]
    pub fn effective(&self, e: f64, mu_p: f64) -> f64 {
        match self {
            Self::Plain {} => e,
            Self::JenkinsZhang(j) => (e - jenkins_zhang_f(mu_p, e, j.e_t)).max(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn jz() -> RestitutionModel {
        RestitutionModel::default()
    }

    #[test]
    fn frictionless_gives_bare_restitution() {
        for e in [0.1, 0.5, 0.7, 1.0] {
            assert_eq!(jz().effective(e, 0.0), e);
            assert_eq!(RestitutionModel::Plain {}.effective(e, 0.4), e);
        }
    }

    #[test]
    fn reference_value() {
        // e = 0.7, mu_p = 0.4 (Chassagne reference case): e_eff = 0.4578 (checked with an
        // independent evaluation of the printed C2-C5 with mu0 = 3.5 mu_p (1+e)).
        assert_relative_eq!(jz().effective(0.7, 0.4), 0.4578, epsilon = 1e-4);
    }

    #[test]
    fn small_friction_asymptote_holds_for_every_e() {
        // f = pi mu/2 - 4.5 mu^2 + O(mu^4): the remainder over mu^3 must vanish with mu,
        // at every e (and e_t), since e enters through mu0 only at order mu^4.
        let pi = std::f64::consts::PI;
        for e in [0.1, 0.3, 0.5, 0.7, 0.9, 1.0] {
            for e_t in [0.0, 0.5] {
                let mut last = f64::INFINITY;
                for mu in [1e-2, 1e-3, 1e-4] {
                    let rem = (jenkins_zhang_f(mu, e, e_t) - (0.5 * pi * mu - 4.5 * mu * mu)) / mu.powi(3);
                    assert!(rem.abs() < 0.5 * last.min(1.0), "e = {e}, mu = {mu}: {rem}");
                    last = rem.abs();
                }
            }
        }
    }

    #[test]
    fn large_friction_saturates() {
        let r = 1.0 / (3.5 * 1.7);
        assert_relative_eq!(jenkins_zhang_f(1e6, 0.7, 0.0), 2.0 * r * (1.0 - r), max_relative = 1e-5);
    }

    #[test]
    fn clamped_at_zero() {
        assert_eq!(jz().effective(0.1, 1.0), 0.0);
        assert!(0.1 - jenkins_zhang_f(1.0, 0.1, 0.0) < 0.0);
    }

    proptest! {
        #[test]
        fn decreasing_in_friction_and_below_e(e in 0.05f64..=1.0, mu in 0.0f64..2.0, dmu in 1e-4f64..0.5, e_t in 0.0f64..1.0) {
            let m = RestitutionModel::JenkinsZhang(JenkinsZhang { e_t });
            let a = m.effective(e, mu);
            let b = m.effective(e, mu + dmu);
            prop_assert!(a <= e && b <= a);
            prop_assert!(jenkins_zhang_f(mu + dmu, e, e_t) > jenkins_zhang_f(mu, e, e_t));
        }

        #[test]
        fn saturation_beyond_one(e in 0.3f64..=1.0) {
            // the change from mu_p = 1 to 2 is small against the change from 0 to 1
            let m = jz();
            let d01 = m.effective(e, 0.0) - m.effective(e, 1.0);
            let d12 = m.effective(e, 1.0) - m.effective(e, 2.0);
            prop_assert!(d12 < 0.1 * d01);
        }
    }
}
