//! Read access to a coupled run's state, for the driver, the reports, tests and benches.

use saltus_core::scene::Scene;

use super::config::Config;
use super::setup::Material;
use super::solver::Lagrangian;
use crate::column::FluidColumn;
use crate::lagrangian::coupling::drag::FluidForces;
use crate::lagrangian::engine::dem::Dem;
use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::stats::statistics::Stats;
use crate::lagrangian::stats::steady::Steady;
use crate::measures::transport_scales::TransportScales;

impl Lagrangian<'_> {
    /// The scene.
    pub fn scene(&self) -> &Scene {
        self.params.scene
    }
    /// Whether the scene has an active fluctuation closure.
    pub fn has_fluctuation(&self) -> bool {
        self.params.fluctuation.is_some()
    }
    /// Configuration.
    pub fn config(&self) -> &Config {
        &self.params.cfg
    }
    /// Time of the flow (s), after the deposition.
    pub fn time(&self) -> f64 {
        self.state.time
    }
    /// DEM steps of the flow.
    pub fn steps(&self) -> u64 {
        self.state.steps
    }
    /// DEM steps of the deposition.
    pub fn settle_steps(&self) -> u64 {
        self.state.settle_steps
    }
    /// DEM time step (s).
    pub fn dt(&self) -> f64 {
        self.state.dem.dt()
    }
    /// DEM steps per fluid period: the fluid updates, and the averaging samples, come at
    /// the flow steps that are multiples of it.
    pub fn fluid_every(&self) -> u64 {
        self.params.fluid_every
    }
    /// The DEM: particles, neighbour list, contact law.
    pub fn dem(&self) -> &Dem {
        &self.state.dem
    }
    /// Particles.
    pub fn particles(&self) -> &Particles {
        &self.state.dem.p
    }
    /// The drag state: fluctuation draws and clocks.
    pub fn forces(&self) -> &FluidForces {
        &self.state.forces
    }
    /// Fluid velocity the particles see, per cell (m/s).
    pub fn fluid_velocity(&self) -> &[f64] {
        &self.state.field.u
    }
    /// Volume fraction per cell of the last fluid update, as the column and the closures
    /// took it.
    pub fn volume_fraction(&self) -> &[f64] {
        &self.state.field.phi
    }
    /// Height of the column bottom in particle coordinates (m).
    pub fn column_base(&self) -> f64 {
        self.state.field.base
    }
    /// Cells of the fluid column.
    pub fn cells(&self) -> usize {
        self.state.field.u.len()
    }
    /// Mobile particles.
    pub fn mobile(&self) -> usize {
        self.state.dem.p.n_mobile
    }
    /// Fluid cell height (m).
    pub fn dz(&self) -> f64 {
        self.state.field.dz
    }
    /// Slice volume A dz (m^3).
    pub fn cell_volume(&self) -> f64 {
        self.state.cell_volume
    }
    /// Running statistics.
    pub fn stats(&self) -> &Stats {
        &self.state.stats
    }
    /// Steady-state test.
    pub fn steady(&self) -> &Steady {
        &self.state.steady
    }

    /// The batched transport rate of the flow: its averaging window (MSER-5) and the rate's
    /// error over it.
    pub fn truncation(&self) -> &crate::lagrangian::stats::truncation::Truncation {
        &self.state.truncation
    }
    /// The fluid column, when coupled.
    pub fn column(&self) -> Option<&FluidColumn> {
        self.state.column.as_ref()
    }
    /// Nominal bed surface above the column bottom (m).
    pub fn bed_surface(&self) -> f64 {
        self.state.bed_surface
    }
    /// Particle diameter and density.
    pub fn material(&self) -> Material {
        self.params.mat
    }
    /// The scales of qs*, Shields and the nominal Shields number.
    pub fn transport_scales(&self) -> TransportScales {
        self.params.scales
    }
    /// Haff's cooling time constant of a homogeneous cooling scene, sqrt(pi) d / (4 (1 -
    /// e^2) phi g0) (s m/s; over sqrt(T0) it is the cooling time): a gas without fluid,
    /// body force or friction in a triply periodic box; `None` for any other scene.
    pub fn haff_constant(&self) -> Option<f64> {
        self.params.haff
    }
    /// Fluid density (kg/m^3).
    pub fn fluid_density(&self) -> f64 {
        self.params.scene.fluid.density
    }
}
