//! Fluid velocity fluctuations seen by particles (family `fluctuation`): none, Maurin's
//! discrete random walk, Cheng's eddy interaction model and the gradient
//! diffusion of a Schmidt number (Chassagne eq 4.4).
//!
//! Random numbers come only from the caller's seeded [`saltus_core::rng::Rng`]; each model
//! documents how many it consumes per draw and in which order.

pub mod drag_reynolds;
pub mod drw;
pub mod eim;
pub mod none;
pub mod schmidt;

pub use drag_reynolds::DragReynoldsNumber;
pub use drw::DiscreteRandomWalk;
pub use eim::EddyInteraction;
pub use none::NoFluctuation;
pub use schmidt::Schmidt;

use saltus_core::{DriftForm, Params};
use serde::{Deserialize, Serialize};

/// Mean-field form of the drift of a fluctuation model (key `mean_field` of `eim`, `drw`
/// and `schmidt`), see [`DriftForm`].
///
/// * `gradient` (default): Chassagne's eq 4.4, flux -D dphi/dz, the well-mixed form (that
///   of a random walk corrected for the gradient of D).
/// * `ito`: flux -d(D phi)/dz, the diffusion limit of the draws of these models, which hold
///   a velocity and a duration fixed where the eddy is drawn: the form under which the
///   Eulerian profile is the one the particle face gives (Cheng's dilute scenes use it).
///
/// Why `gradient` is the default: its flux vanishes in a uniform bed whatever D does there,
/// while the Ito drift phi grad(D) acts on packed grains too; with the k-omega start-up
/// (nu_t = 0.15 m^2/s inside the packed bed of the Revil-Baudard sheet flow) the Ito form
/// breaks the bed in the first 2e-4 s, the gradient form does not.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum MeanField {
    /// flux -D dphi/dz (Chassagne eq 4.4)
    #[default]
    Gradient,
    /// flux -d(D phi)/dz, the diffusion limit of the draws
    Ito,
}

impl MeanField {
    /// The solver's form of this choice.
    pub fn form(self) -> DriftForm {
        match self {
            Self::Ito => DriftForm::Ito,
            Self::Gradient => DriftForm::Gradient,
        }
    }
}

#[cfg(test)]
pub(crate) mod sim {
    //! What the diffusivity tests share: a tracer random walk driven by a model's
    //! own draws and durations.

    use saltus_core::rng::{stream, Rng};
    use saltus_core::{FlowScales, Fluctuation, ParticleSlip, TurbulencePoint};

    /// Vertical displacements after time `t_end` of `n` tracers (zero slip), each with its
    /// own stream `i` of `seed`. `phase` gives the fraction of the first eddy still to run
    /// at t = 0 (1 for a fresh eddy); it is called with the tracer's stream.
    pub fn displacements(
        model: &dyn Fluctuation,
        tp: &TurbulencePoint,
        s: &FlowScales,
        n: usize,
        t_end: f64,
        seed: u64,
        phase: &dyn Fn(&mut Rng) -> f64,
    ) -> Vec<f64> {
        let slip = ParticleSlip::default();
        (0..n)
            .map(|i| {
                let mut rng = stream(seed, i as u64);
                let first = model.draw(tp, &slip, s, &mut rng);
                let mut t = first.duration * phase(&mut rng);
                let mut z = first.u[2] * t.min(t_end);
                while t < t_end {
                    let d = model.draw(tp, &slip, s, &mut rng);
                    let hold = d.duration.min(t_end - t);
                    z += d.u[2] * hold;
                    t += d.duration;
                }
                z
            })
            .collect()
    }

    /// Mean and standard error of the sample mean of `x`.
    pub fn mean_se(x: &[f64]) -> (f64, f64) {
        let n = x.len() as f64;
        let m = x.iter().sum::<f64>() / n;
        let v = x.iter().map(|a| (a - m) * (a - m)).sum::<f64>() / (n - 1.0);
        (m, (v / n).sqrt())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_fluctuation_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::Fluctuation>(saltus_core::closure::Family::Fluctuation);
    }
}
