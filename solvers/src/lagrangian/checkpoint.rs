//! The state of a Lagrangian run as a checkpoint ([`crate::run::checkpoint`]): everything
//! the steps to come read, so that a restart goes on bit for bit.
//!
//! Saved: the phase and its counters (deposition steps, flow steps and time), the DEM
//! (particles with their velocities and angular velocities, the neighbour list as built,
//! with its reference positions, pair order and tangential springs, the wall-contact
//! springs, the body force of the phase, the rebuild flag), the drag state (every
//! particle's random stream, fluctuation draw and clock, the slip and drag coefficient of
//! the last evaluation), the fluid field the particles see, the fluid column (velocity,
//! relaxed eddy viscosity, k and omega), the last averages, the statistics accumulators (the granular fields' too),
//! the steady-state detector, the deposit surface and the VTK counters. The neighbour list
//! is saved rather than rebuilt: a rebuild at another step would wrap the positions and
//! order the pairs differently, and the sums would round differently.
//!
//! Not saved: what the scene gives (closures, contact law, time step, fluid period, box,
//! thread pool: the restart sets the solver up from the same scene first) and the scratch
//! that every step refills.

use bincode::Options as _;
use serde::{Deserialize, Serialize};

use super::averaging::CellSums;
use super::dem::Dem;
use super::drag::{FluidField, FluidForces};
use super::granular::GranularStats;
use super::solver::{Lagrangian, Stage};
use super::stats::{Stats, Steady};
use crate::column::FluidColumn;

/// The state as written (borrowed from the solver).
#[derive(Serialize)]
struct Saving<'s> {
    stage: Stage,
    time: f64,
    steps: u64,
    settle_steps: u64,
    dem: &'s Dem,
    forces: &'s FluidForces,
    field: &'s FluidField,
    column: &'s Option<FluidColumn>,
    sums: &'s CellSums,
    averages: [&'s [f64]; 4],
    stats: &'s Stats,
    granular: &'s Option<GranularStats>,
    steady: &'s Steady,
    cell_volume: f64,
    bed_surface: f64,
    vtk: &'s Option<super::vtk::Series>,
    next_vtk: f64,
    flow_wall: f64,
}

/// The state as read: [`Saving`] field by field.
#[derive(Deserialize)]
struct Saved {
    stage: Stage,
    time: f64,
    steps: u64,
    settle_steps: u64,
    dem: Dem,
    forces: FluidForces,
    field: FluidField,
    column: Option<FluidColumn>,
    sums: CellSums,
    averages: [Vec<f64>; 4],
    stats: Stats,
    granular: Option<GranularStats>,
    steady: Steady,
    cell_volume: f64,
    bed_surface: f64,
    vtk: Option<super::vtk::Series>,
    next_vtk: f64,
    flow_wall: f64,
}

fn options() -> impl bincode::Options {
    bincode::DefaultOptions::new()
}

impl Lagrangian<'_> {
    /// Append the state to `out`.
    pub(super) fn save_state(&self, out: &mut Vec<u8>) -> Result<(), String> {
        let s = Saving {
            stage: self.stage,
            time: self.time,
            steps: self.steps,
            settle_steps: self.settle_steps,
            dem: &self.dem,
            forces: &self.forces,
            field: &self.field,
            column: &self.column,
            sums: &self.sums,
            averages: [&self.phi, &self.u_p, &self.beta, &self.tau_t],
            stats: &self.stats,
            granular: &self.granular,
            steady: &self.steady,
            cell_volume: self.cell_volume,
            bed_surface: self.bed_surface,
            vtk: &self.vtk,
            next_vtk: self.next_vtk,
            flow_wall: self.flow_wall,
        };
        options().serialize_into(out, &s).map_err(|e| format!("cannot encode the DEM state: {e}"))
    }

    /// Take the state [`Lagrangian::save_state`] wrote, after checking that its sizes fit
    /// together and this scene (a state that does not is refused, never indexed).
    pub(super) fn restore_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let s: Saved = options()
            .with_limit(bytes.len() as u64)
            .deserialize(bytes)
            .map_err(|e| format!("cannot decode the DEM state: {e}"))?;
        let p = s.dem.particles();
        let n = p.len();
        let cells = s.field.u.len();
        let particle_arrays = [&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz, &p.radius, &p.inv_mass];
        let cell_arrays = [&s.field.phi, &s.field.nu_t, &s.field.reynolds, &s.field.re_ratio, &s.sums.vol];
        let fits = p.n_mobile <= n
            && particle_arrays.iter().all(|a| a.len() == n)
            && p.inv_inertia.len() == n
            && s.forces.fluctuations().len() == n
            && s.forces.eddy_clocks().len() == n
            && s.dem.ext.iter().all(|e| e.len() == p.n_mobile)
            && cells > 0
            && cell_arrays.iter().all(|a| a.len() == cells)
            && s.averages.iter().all(|a| a.len() == cells)
            && s.column.as_ref().is_none_or(|c| c.velocity().len() == cells)
            && s.column.is_some() == self.column.is_some()
            && s.granular.is_some() == self.granular.is_some()
            && s.granular.as_ref().is_none_or(|g| g.fits(cells))
            && s.dem.dt() == self.dem.dt();
        if !fits {
            return Err(format!(
                "the DEM state does not fit this scene ({n} particles, {cells} fluid cells, time step {:e} s)",
                s.dem.dt()
            ));
        }
        let [phi, u_p, beta, tau_t] = s.averages;
        self.stage = s.stage;
        self.time = s.time;
        self.steps = s.steps;
        self.settle_steps = s.settle_steps;
        self.dem = s.dem;
        self.forces = s.forces;
        self.field = s.field;
        self.field.refresh();
        self.field.set_bed_threshold(self.fluctuation.and_then(|f| f.above_bed()));
        self.column = s.column;
        self.sums = s.sums;
        (self.phi, self.u_p, self.beta, self.tau_t) = (phi, u_p, beta, tau_t);
        self.stats = s.stats;
        self.granular = s.granular;
        self.steady = s.steady;
        self.cell_volume = s.cell_volume;
        self.bed_surface = s.bed_surface;
        self.vtk = s.vtk;
        self.next_vtk = s.next_vtk;
        self.flow_wall_before = s.flow_wall;
        self.flow_wall = s.flow_wall;
        self.zero_faces = vec![0.0; cells + 1];
        Ok(())
    }
}
