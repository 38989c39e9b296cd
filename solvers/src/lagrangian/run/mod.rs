//! The Lagrangian solver of a scene: its configuration, the set-up of the particles and
//! walls, the resolved parameters, the state and the workspace, the stepping (DEM steps,
//! fluid updates, checks), the deposition and the sampling. Uses [`super::engine`],
//! [`super::coupling`] and [`super::stats`].

mod access;
pub mod config;
mod deposition;
pub mod params;
mod sampling;
pub mod setup;
pub mod solver;
pub mod state;
mod stepping;
pub mod warm;
pub mod workspace;

/// The stages of a flow step whose wall time the solver counts besides the engine's
/// ([`crate::lagrangian::engine::dem::STAGES`]): the drag on the grains, the fluid
/// column's solve and the field refresh, the cell averages, and the statistics and
/// granular-field samples.
pub const STAGES: [&str; 4] = ["drag", "fluid_column", "averaging", "sampling"];

/// Indices into [`STAGES`].
pub(crate) mod stage {
    pub(crate) const DRAG: usize = 0;
    pub(crate) const COLUMN: usize = 1;
    pub(crate) const AVERAGING: usize = 2;
    pub(crate) const SAMPLING: usize = 3;
}
