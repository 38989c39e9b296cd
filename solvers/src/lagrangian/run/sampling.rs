//! The averaging samples of the granular fields ([`crate::lagrangian::stats::granular`]): when a flow step
//! takes one, the slices it is taken on, the sample of a run without fluid, and the
//! averages the report writes.

use super::config::FluidMode;
use super::solver::Lagrangian;
use super::stepping::average;
use crate::lagrangian::engine::contact_sums::Slices;
use crate::lagrangian::stats::granular::{FieldScales, GranularAverages};

impl Lagrangian<'_> {
    /// The averaging slices (the fluid cells) in particle coordinates.
    pub fn slices(&self) -> Slices {
        self.state.slices()
    }

    /// Whether the fluid update (or dry sample) of this flow step takes an averaging
    /// sample.
    pub(crate) fn sample_due(&self) -> bool {
        let n = &self.params.cfg.settings.numerics;
        n.takes_samples() && self.state.time >= n.stats_start
    }

    /// Add the granular fields of the step just taken (a sampled one) to their sums.
    pub(crate) fn sample_granular(&mut self) {
        let slices = self.slices();
        if let Some(g) = self.state.granular.as_mut() {
            let forces = &self.state.forces;
            g.add(self.state.dem.contact_sums(), &self.state.dem.p, &slices, |a| forces.force(a));
        }
    }

    /// An averaging sample of a run without fluid (one that asks for the granular
    /// fields): the particle sums and the granular fields, the fluid columns at rest.
    pub(crate) fn dry_sample(&mut self) {
        average(&self.params, &mut self.state, &mut self.work);
        let qs = self.state.transport_rate();
        let zeros = &self.work.zero_faces[..self.state.field.u.len()];
        self.state.stats.add(&self.state.sums, &self.state.field.u, zeros, zeros, zeros, &self.work.zero_faces, qs);
        self.sample_granular();
    }

    /// The time-averaged granular fields, when the scene asks for them and the run took
    /// samples.
    pub fn granular_averages(&self) -> Option<GranularAverages> {
        let g = self.state.granular.as_ref().filter(|g| g.samples > 0)?;
        let scene = self.params.scene;
        let wet = self.params.cfg.settings.numerics.fluid != FluidMode::Off;
        let scales = FieldScales {
            rho_p: self.params.mat.rho_p,
            d: self.params.mat.d,
            eta_f: wet.then_some(scene.fluid.density * scene.fluid.viscosity),
        };
        Some(g.averages(&self.state.stats, self.state.cell_volume, self.state.field.dz, &scales))
    }
}
