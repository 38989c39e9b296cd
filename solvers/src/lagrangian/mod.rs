//! # Lagrangian solver: soft-sphere DEM coupled to the 1D fluid column (Maurin et al. 2015)
//!
//! One folder per stage; imports run one way, `engine <- coupling <- stats <- run <- output`,
//! and `stepper.rs` joins the run and its outputs for the driver:
//!
//! - [`engine`]: the dry DEM step (particles, contact laws, walls, half-cylinders,
//!   neighbour list, pair loop, chunking, the contact sums of a sampled step); it knows
//!   nothing of the fluid;
//! - [`coupling`]: the fluid as the grains see it, the drag on them, the cell averages and
//!   the momentum exchange with the column;
//! - [`stats`]: time averages, block errors, the steady-state test, Haff's cooling, the
//!   granular fields;
//! - [`run`]: the solver (parameters, state with its checkpoint serialisation, workspace),
//!   its stepping, the deposition, the set-up and the configuration;
//! - [`output`]: the report and the ParaView documents.

pub mod coupling;
pub mod engine;
pub mod output;
pub mod run;
pub mod stats;
mod stepper;

pub use engine::contact::{ContactLaw, ContactModel};
pub use engine::cylinders::HalfCylinders;
pub use engine::dem::Dem;
pub use engine::neighbours::NeighbourList;
pub use engine::particles::{Box3, Particles};
pub use engine::walls::Wall;
pub use run::config::{Bottom, Config, Domain, FluidMode, Initial, Settings, Surface};
pub use run::solver::{Lagrangian, CHECK_STEPS, MAX_OVERLAP, MAX_SPEED};
