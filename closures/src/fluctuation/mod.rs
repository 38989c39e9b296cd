//! Fluid velocity fluctuations seen by particles (family `fluctuation`): none, Maurin's
//! discrete random walk, Cheng's eddy interaction model and the gradient
//! diffusion of a Schmidt number (Chassagne eq 4.4).
//!
//! Random numbers come only from the caller's seeded [`saltus_core::rng::Rng`]; each model
//! documents how many it consumes per draw and in which order.

pub mod drw;
pub mod eim;
pub mod none;
pub mod schmidt;

pub use drw::DiscreteRandomWalk;
pub use eim::EddyInteraction;
pub use none::NoFluctuation;
pub use schmidt::Schmidt;

#[cfg(test)]
pub(crate) mod sim {
    //! Shared helper of the diffusivity tests: a tracer random walk driven by a model's
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
