//! The averaging samples of the granular fields ([`super::granular`]): when a flow step
//! takes one, the slices it is taken on, the sample of a run without fluid, and the
//! averages the report writes.

use super::config::FluidMode;
use super::granular::{FieldScales, GranularAverages, Slices};
use super::solver::Lagrangian;

impl Lagrangian<'_> {
    /// The averaging slices (the fluid cells) in particle coordinates.
    pub fn slices(&self) -> Slices {
        Slices { base: self.field.base, dz: self.field.dz, n: self.field.u.len() }
    }

    /// Whether the fluid update (or dry sample) of this flow step takes an averaging
    /// sample.
    pub(super) fn sample_due(&self) -> bool {
        let n = &self.cfg.settings.numerics;
        n.takes_samples() && self.time >= n.stats_start
    }

    /// Add the granular fields of the step just taken (a sampled one) to their sums.
    pub(super) fn sample_granular(&mut self) {
        let slices = self.slices();
        if let Some(g) = self.granular.as_mut() {
            let forces = &self.forces;
            g.add(self.dem.contact_sums(), &self.dem.p, &slices, |a| forces.force(a));
        }
    }

    /// An averaging sample of a run without fluid (one that asks for the granular
    /// fields): the particle sums and the granular fields, the fluid columns at rest.
    pub(super) fn dry_sample(&mut self) {
        self.average();
        let qs: f64 = self.sums.v[0].iter().sum::<f64>() / (self.cell_volume / self.field.dz);
        let zeros = &self.zero_faces[..self.field.u.len()];
        self.stats.add(&self.sums, &self.field.u, zeros, zeros, zeros, &self.zero_faces, qs);
        self.sample_granular();
    }

    /// The time-averaged granular fields, when the scene asks for them and the run took
    /// samples.
    pub fn granular_averages(&self) -> Option<GranularAverages> {
        let g = self.granular.as_ref().filter(|g| g.samples > 0)?;
        let scene = self.scene;
        let wet = self.cfg.settings.numerics.fluid != FluidMode::Off;
        let scales = FieldScales {
            rho_p: self.mat.rho_p,
            d: self.mat.d,
            eta_f: wet.then_some(scene.fluid.density * scene.fluid.viscosity),
        };
        Some(g.averages(&self.stats, self.cell_volume, self.field.dz, &scales))
    }
}
