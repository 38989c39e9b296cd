//! A warm start of the DEM: the flow starts from the grains of another run's final
//! checkpoint (the neighbouring point of a sweep, with another forcing) instead of from a
//! deposition of its own.
//!
//! Carried: the particles (positions, velocities, spins, the fixed ones of the bottom)
//! with their contact histories and neighbour list, and the half-cylinders of a Frey
//! bottom (the grains lie on them). Rebuilt from this scene: the body force, the fluid
//! column (cells, depth, at rest; with `surface = "deposit"` its free surface
//! `water_depth` above the surface the carried deposit had at rest, as the parent's
//! deposition measured it and every warm start since carried it),
//! every grain's fluid forces and random stream from this scene's seed, the statistics,
//! the granular fields, the steady-state test and the time series, all empty, and the
//! clocks at zero; the deposition is skipped. The statistics' `stats_start` is counted
//! from the warm start.
//!
//! Refused ([`refusal`]): a checkpoint of another solver, a run that ended in its
//! deposition, and a scene that differs from the checkpoint's in a key that makes other
//! grains or gives them another meaning ([`GRAIN_KEYS`]: their count, sizes and
//! material, the contact law and time step, the lateral cell, the walls and the bottom,
//! and where the free surface stands).

use saltus_core::scene::Scene;

use super::config::FluidMode;
use super::solver::Lagrangian;
use super::state::{self, Stage, State};
use crate::run::checkpoint::{scene_differences_in, Restart};

/// Keys of a resolved scene (with the keys under them) that must be the checkpoint's for
/// its grains to start this scene's flow: the particles' count (`particles`,
/// `bed_height`, `bed_phi`, `gas_phi`, the list), sizes, material and contact law (and
/// with them the time step, `dt_safety`, and the Verlet skin of the carried list), the
/// lateral cell, the walls and the bottom, and `surface` and `fluid` (the carried
/// deposit's surface is the level the free surface stands above, measured only where the
/// parent fitted a fluid column to its deposit).
pub const GRAIN_KEYS: [&str; 19] = [
    "particles",
    "domain.bed_height",
    "domain.bed_phi",
    "solver.lagrangian.length",
    "solver.lagrangian.width",
    "solver.lagrangian.side_walls",
    "solver.lagrangian.bottom",
    "solver.lagrangian.rough_layer",
    "solver.lagrangian.height",
    "solver.lagrangian.initial",
    "solver.lagrangian.particles",
    "solver.lagrangian.size_dispersion",
    "solver.lagrangian.gas_phi",
    "solver.lagrangian.particle_list",
    "solver.lagrangian.dt_safety",
    "solver.lagrangian.skin",
    "solver.lagrangian.surface",
    "solver.lagrangian.fluid",
    "solver.type",
];

/// Why the state of checkpoint `r` cannot start the flow of `scene`, if it cannot: read
/// before anything is set up, so that the caller may start from rest instead.
pub fn refusal(scene: &Scene, r: &Restart) -> Option<String> {
    let file = r.file.display();
    if r.solver != "lagrangian" {
        return Some(format!("{file}: written by the {} solver, not by the DEM", r.solver));
    }
    let now = match scene.to_toml() {
        Ok(t) => t,
        Err(e) => return Some(e.to_string()),
    };
    match scene_differences_in(&r.resolved_scene(&scene.path), &now, &GRAIN_KEYS) {
        Err(e) => return Some(format!("{file}: {e}")),
        Ok(keys) if !keys.is_empty() => {
            return Some(format!("{file}: other grains: the scene differs in {}", keys.join(", ")));
        }
        Ok(_) => {}
    }
    match state::decode(&r.state) {
        Err(e) => Some(format!("{file}: {e}")),
        Ok(s) => flow_state(&s).err().map(|e| format!("{file}: {e}")),
    }
}

/// A state whose flow has started (its grains are deposited).
fn flow_state(s: &State) -> Result<(), String> {
    match s.stage {
        Stage::Flow => Ok(()),
        Stage::Deposition => Err("the run ended in its deposition: its grains are not deposited".into()),
    }
}

impl Lagrangian<'_> {
    /// Start the flow from the grains of `parent` ([`refusal`] says which states fit). A
    /// state that does not fit is refused before anything changes.
    pub(crate) fn warm_start_from(&mut self, parent: State) -> Result<(), String> {
        flow_state(&parent)?;
        let (dem, own) = (&parent.dem, &self.state.dem);
        if dem.dt() != own.dt() {
            return Err(format!("the time step differs: {:e} s in the state, {:e} s here", dem.dt(), own.dt()));
        }
        if !dem.same_bounds(own) {
            return Err("the box, the walls or the bottom differ from this scene's".into());
        }
        // A moving bed measured as a deposit lies up to half a diameter below the same
        // grains at rest (its top grains spread over the saltation layer), so the free
        // surface is put above the surface the chain's deposit had at rest, as a point
        // from rest puts it; `surface` and `fluid` are grain keys, so the carried value
        // is a measured deposit wherever this scene fits its column to one.
        let deposit = parent.bed_surface;
        let mut dem = parent.dem;
        dem.body = self.params.flow_body;
        self.state.dem = dem;
        self.state.settle_steps = 0;
        self.start_flow(Some(deposit)).map_err(|b| format!("the column on the carried bed: {b}"))?;
        if self.params.cfg.settings.numerics.fluid != FluidMode::Off {
            // the first drag and the first row of the time series see the carried bed
            self.average();
        }
        Ok(())
    }
}
