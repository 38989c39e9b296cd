//! The averaging of the grains on the cells (the volume fraction, velocity and drag the
//! fluid sees), the samples of the granular fields
//! ([`crate::lagrangian::stats::granular`]): when a flow step takes one, the slices it is
//! taken on, the sample of a run without fluid, and the averages the report writes.

use std::time::Instant;

use saltus_core::scene::DragVelocity;

use super::config::FluidMode;
use super::params::Params;
use super::solver::Lagrangian;
use super::stage;
use super::state::State;
use super::workspace::Workspace;
use crate::lagrangian::coupling::averaging::Seen;
use crate::lagrangian::coupling::smoothing;
use crate::lagrangian::engine::contact_sums::Slices;
use crate::lagrangian::stats::granular::{FieldScales, GranularAverages};

/// Average the particles on the cells and refresh phi (and the hindrance convention)
/// the particles see.
pub(crate) fn average(params: &Params, state: &mut State, work: &mut Workspace) {
    let t0 = Instant::now();
    let (k, urx) = (&state.forces.k, &state.forces.urx);
    let seen = match params.cfg.settings.numerics.drag_velocity {
        DragVelocity::Centre => Seen::Centre,
        DragVelocity::SphereAverage => {
            // one per particle even where no drag was evaluated (a dry run's samples)
            work.seen.resize(state.dem.p.len(), 0.0);
            Seen::SphereAverage(&work.seen)
        }
    };
    state.sums.accumulate(&state.dem.p, state.field.base, state.field.dz, k, urx, seen);
    let u_f: &[f64] = match &state.column {
        Some(c) => c.velocity(),
        None => &state.field.u,
    };
    state.sums.coupling(state.cell_volume, u_f, &mut state.phi, &mut state.u_p, &mut state.beta);
    // the fluid's volume fraction: eq 14's mean over the period's DEM steps, then
    // eq 17's diffusion (Cheng et al.; coupling::smoothing); the reported averages
    // keep the slices of this step
    state.phi_window.take_mean(state.cell_volume, &mut state.phi);
    let l_d = params.cfg.settings.numerics.phi_diffusion;
    if l_d > 0.0 {
        let a = (l_d * params.mat.d / state.field.dz).powi(2);
        smoothing::diffuse(&mut state.phi, a, &mut work.diffusion);
    }
    for (c, &phi) in state.phi.iter().enumerate() {
        state.field.phi[c] = phi.min(0.99);
        state.field.re_ratio[c] = params.hindrance.reynolds_convention().ratio(phi.min(0.99));
    }
    state.field.set_bed_threshold(params.fluctuation.and_then(|f| f.above_bed()));
    if params.re_free_hindrance {
        let n = state.field.phi.len();
        state.field.hindrance.resize(n, 1.0);
        // Re_p does not matter for such a closure
        params.hindrance.factor_batch(&state.field.phi, &work.zero_faces[..n], &mut state.field.hindrance);
    }
    work.stages.lap(stage::AVERAGING, t0);
}

/// Whether the fluid update (or dry sample) of the flow step that starts at `state`
/// takes an averaging sample.
pub(crate) fn sample_due(params: &Params, state: &State) -> bool {
    let n = &params.cfg.settings.numerics;
    n.takes_samples() && state.time >= n.stats_start
}

/// Add the granular fields of the step just taken (a sampled one) to their sums.
pub(crate) fn sample_granular(state: &mut State) {
    let slices = state.slices();
    let State { granular, forces, dem, .. } = state;
    if let Some(g) = granular.as_mut() {
        g.add(dem.contact_sums(), &dem.p, &slices, |a| forces.force(a));
    }
}

/// An averaging sample of a run without fluid (one that asks for the granular fields):
/// the particle sums and the granular fields, the fluid columns at rest.
pub(crate) fn dry_sample(params: &Params, state: &mut State, work: &mut Workspace) {
    average(params, state, work);
    let qs = state.transport_rate();
    let zeros = &work.zero_faces[..state.field.u.len()];
    state.stats.add(&state.sums, &state.field.u, zeros, zeros, zeros, &work.zero_faces, qs);
    sample_granular(state);
}

impl Lagrangian<'_> {
    /// The averaging slices (the fluid cells) in particle coordinates.
    pub fn slices(&self) -> Slices {
        self.state.slices()
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
