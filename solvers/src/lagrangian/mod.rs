//! # Lagrangian solver: soft-sphere DEM coupled to the 1D fluid column (Maurin et al. 2015)

mod access;
pub mod averaging;
pub mod blocking;
mod checkpoint;
pub mod config;
pub mod contact;
pub mod cylinders;
pub mod dem;
mod deposition;
pub mod drag;
pub mod granular;
pub mod neighbours;
mod pairs;
pub mod particles;
pub mod report;
mod sampling;
pub mod setup;
pub mod solver;
pub mod stats;
pub mod stepper;
pub mod vtk;

pub use config::{Bottom, Config, Domain, FluidMode, Initial, Settings, Surface};
pub use contact::{ContactLaw, ContactModel};
pub use cylinders::HalfCylinders;
pub use dem::{Dem, Wall};
pub use neighbours::NeighbourList;
pub use particles::{Box3, Particles};
pub use solver::{Lagrangian, CHECK_STEPS, MAX_SPEED};
