//! A warm start of the DEM: the flow starts from the grains of another run's final
//! checkpoint (the neighbouring point of a sweep, with another forcing) instead of from a
//! deposition of its own.
//!
//! Carried: the particles (positions, velocities, spins, the fixed ones of the bottom)
//! with their contact histories and neighbour list, and the half-cylinders of a Frey
//! bottom (the grains lie on them); and the fluid column (velocity, eddy viscosity, k and
//! omega) and the field the grains see when the checkpoint's scene has this one's
//! forcing and column ([`FLUID_KEYS`]) and the column the same cells (a developed state of
//! the same case starts developed), with the statistical inefficiency of the parent's
//! averaging window as a floor under this run's error
//! (`crate::lagrangian::stats::truncation`). Rebuilt from this scene: the body force, the fluid
//! column otherwise (cells, depth, at rest; with `surface = "deposit"` its free surface
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
//!
//! A start from profiles (`Lagrangian::start_from_profiles`): the grains are this
//! scene's own, deposited as from rest; at the end of the deposition the fluid column
//! takes the profiles' u_f and every mobile grain the profiles' u_p at its centre, the
//! profiles' bed surface put on the deposit's (each the highest level at half the largest
//! packing). A two-fluid steady state of the same scene so gives the flow its velocities
//! from the first step; the packing stays the deposit's.

use std::borrow::Cow;

use saltus_core::scene::Scene;

use super::config::FluidMode;
use super::sampling::average;
use super::solver::Lagrangian;
use super::state::{self, Stage, State};
use crate::output::Profiles;
use crate::run::checkpoint::{scene_differences_in, Restart};
use crate::run::start_profiles::StartProfiles;
use crate::run::{Breakdown, Place};

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

/// Keys of a resolved scene that must be the checkpoint's for its fluid column to be
/// carried too: the fluid, the forcing and the body force, the column's depth and cells,
/// the fluid period and the closures the column reads.
pub const FLUID_KEYS: [&str; 9] = [
    "fluid",
    "physics",
    "domain.water_depth",
    "solver.lagrangian.cells",
    "solver.lagrangian.fluid_period",
    "closures.turbulence",
    "closures.viscosity",
    "closures.drag",
    "closures.hindrance",
];

/// Whether the fluid column of checkpoint `r` is carried into `scene`'s flow (see
/// [`FLUID_KEYS`]).
pub fn carries_fluid(scene: &Scene, r: &Restart) -> bool {
    scene.to_toml().is_ok_and(|now| {
        scene_differences_in(&r.resolved_scene(&scene.path), &now, &FLUID_KEYS).is_ok_and(|k| k.is_empty())
    })
}

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
    /// Start the flow from the grains of `parent` ([`refusal`] says which states fit), with
    /// its fluid column when `fluid` ([`carries_fluid`]) and the column has the same cells.
    /// A state that does not fit is refused before anything changes.
    pub(crate) fn warm_start_from(&mut self, parent: State, fluid: bool) -> Result<(), String> {
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
        let same_cells = |c: &crate::column::FluidColumn| {
            self.state.column.as_ref().is_some_and(|own| own.grid().faces() == c.grid().faces())
        };
        if fluid && parent.column.as_ref().is_some_and(same_cells) && parent.field.u.len() == self.state.field.u.len() {
            let time = self.state.column.as_ref().map_or(0.0, |c| c.time());
            self.state.column = parent.column;
            if let Some(c) = self.state.column.as_mut() {
                c.set_time(time);
            }
            self.state.field = parent.field;
            self.state.field.refresh();
            self.state.field.set_bed_threshold(self.params.fluctuation.and_then(|f| f.above_bed()));
            // a developed state of the same case: its longer window knows the correlation
            // time of qs(t) better than this run's first seconds do
            self.state.truncation.set_prior(parent.truncation.inefficiency_s());
        }
        if self.params.cfg.settings.numerics.fluid != FluidMode::Off {
            // the first drag and the first row of the time series see the carried bed
            average(&self.params, &mut self.state, &mut self.work);
        }
        Ok(())
    }

    /// Start the flow with the velocities of `p` (another run's final profiles): at the
    /// end of the deposition ([`Lagrangian::start_with`]), or at once for a scene without
    /// one. Refused: a run whose fluid is not coupled (no column to take u_f), profiles
    /// that cannot start a run ([`StartProfiles::new`]) or hold no grains (no bed surface
    /// to align), and a run that has started.
    pub(crate) fn start_from_profiles(&mut self, p: &Profiles) -> Result<(), String> {
        if self.state.column.is_none() {
            return Err("the profiles start a coupled fluid column: this scene's fluid is not coupled".into());
        }
        let start = StartProfiles::new(p, false)?;
        if start.bed_surface().is_none() {
            return Err("the profiles hold no grains: there is no bed surface to put on the deposit's".into());
        }
        match self.state.stage {
            Stage::Deposition if self.state.settle_steps == 0 => {
                self.state.start = Some(start);
                Ok(())
            }
            Stage::Flow if self.state.steps == 0 => self.start_with(&start).map_err(|b| b.to_string()),
            _ => Err("the run has started: profiles start a run at its beginning only".into()),
        }
    }

    /// The fluid column takes u_f of `start` and every mobile grain u_p at its centre
    /// (spins and the other components at zero), `start`'s bed surface put on the
    /// deposit's.
    pub(super) fn start_with(&mut self, start: &StartProfiles) -> Result<(), Breakdown> {
        let Some(surface) = start.bed_surface() else { return Ok(()) };
        // z in the profiles = z above the column bottom - shift
        let shift = self.measure_deposit_surface() - surface;
        if let Some(column) = self.state.column.as_mut() {
            let u: Vec<f64> = column.grid().centres().iter().map(|&z| start.u_f(z - shift)).collect();
            column.set_velocity(&u).map_err(|e| Breakdown {
                time: 0.0,
                place: Place::Column,
                field: Cow::Borrowed("u_f"),
                value: u.len() as f64,
                reason: format!("the starting profiles: {e}"),
            })?;
            let field = &mut self.state.field;
            let n = field.u.len().min(u.len());
            field.u[..n].copy_from_slice(&u[..n]);
            field.refresh();
        }
        let base = self.state.field.base;
        let p = &mut self.state.dem.p;
        for a in 0..p.n_mobile {
            p.vx[a] = start.u_p(p.z[a] - base - shift);
            p.vy[a] = 0.0;
            p.vz[a] = 0.0;
            p.wx[a] = 0.0;
            p.wy[a] = 0.0;
            p.wz[a] = 0.0;
        }
        if self.params.cfg.settings.numerics.fluid != FluidMode::Off {
            average(&self.params, &mut self.state, &mut self.work);
        }
        Ok(())
    }
}
