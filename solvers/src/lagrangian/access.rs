//! Read access to a coupled run's state, for the driver, the reports and the checkpoints.

use saltus_core::scene::Scene;

use super::config::Config;
use super::dem::Dem;
use super::drag::FluidForces;
use super::particles::Particles;
use super::setup::Material;
use super::solver::Lagrangian;
use super::stats::{Stats, Steady};
use crate::column::FluidColumn;

impl Lagrangian<'_> {
    /// The scene.
    pub fn scene(&self) -> &Scene {
        self.scene
    }
    /// Whether the scene has an active fluctuation closure.
    pub fn has_fluctuation(&self) -> bool {
        self.fluctuation.is_some()
    }
    /// Configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }
    /// Time of the flow (s), after the deposition.
    pub fn time(&self) -> f64 {
        self.time
    }
    /// DEM steps of the flow.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// DEM steps of the deposition.
    pub fn settle_steps(&self) -> u64 {
        self.settle_steps
    }
    /// DEM time step (s).
    pub fn dt(&self) -> f64 {
        self.dem.dt()
    }
    /// DEM steps per fluid period: the fluid updates, and the averaging samples, come at
    /// the flow steps that are multiples of it.
    pub fn fluid_every(&self) -> u64 {
        self.fluid_every
    }
    /// The DEM: particles, neighbour list, contact law.
    pub fn dem(&self) -> &Dem {
        &self.dem
    }
    /// Particles.
    pub fn particles(&self) -> &Particles {
        &self.dem.p
    }
    /// The drag state: fluctuation draws and clocks.
    pub fn forces(&self) -> &FluidForces {
        &self.forces
    }
    /// Fluid velocity the particles see, per cell (m/s).
    pub fn fluid_velocity(&self) -> &[f64] {
        &self.field.u
    }
    /// Cells of the fluid column.
    pub fn cells(&self) -> usize {
        self.field.u.len()
    }
    /// Wall-clock time of the flow phase so far (s), for the throughput.
    pub fn flow_wall(&self) -> f64 {
        self.flow_wall
    }
    /// Mobile particles.
    pub fn mobile(&self) -> usize {
        self.dem.p.n_mobile
    }
    /// Fluid cell height (m).
    pub fn dz(&self) -> f64 {
        self.field.dz
    }
    /// Slice volume A dz (m^3).
    pub fn cell_volume(&self) -> f64 {
        self.cell_volume
    }
    /// Running statistics.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }
    /// Steady-state test.
    pub fn steady(&self) -> &Steady {
        &self.steady
    }
    /// The fluid column, when coupled.
    pub fn column(&self) -> Option<&FluidColumn> {
        self.column.as_ref()
    }
    /// Nominal bed surface above the column bottom (m).
    pub fn bed_surface(&self) -> f64 {
        self.bed_surface
    }
    /// Particle diameter and density.
    pub fn material(&self) -> Material {
        self.mat
    }
    /// Haff's cooling time constant of a homogeneous cooling scene, sqrt(pi) d / (4 (1 -
    /// e^2) phi g0) (s m/s; over sqrt(T0) it is the cooling time): a gas without fluid,
    /// body force or friction in a triply periodic box; `None` for any other scene.
    pub fn haff_constant(&self) -> Option<f64> {
        self.haff
    }
}
