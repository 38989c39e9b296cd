//! # saltus-core
//!
//! Units-free SI types, closure **traits**, the parameter/validation vocabulary shared by
//! every closure, the model registry and the declarative scene schema of saltus.
//!
//! Models live in `saltus-closures`; algorithms in `saltus-solvers`. This crate holds no
//! physics beyond the contracts that the two sides agree on, and the
//! [`grain`] geometry and hard-sphere packing that both evaluate.
//!
//! ## Adding a closure from outside the workspace
//!
//! Implement the family trait (say [`DragLaw`]) for a `Serialize + Deserialize` struct, mark
//! the impl with `#[typetag::serde(name = "my_law")]`, implement [`Describe`] and register a
//! default instance with [`register_model!`]. The scene format then accepts
//! `[closures.drag] type = "my_law"` and `saltus models` lists it. `#[derive(Describe)]`
//! writes the [`Describe`] impl from attributes; `examples/custom_closure` is a whole crate
//! and `docs/extending.md` the walk-through.

pub mod closure;
pub mod data;
pub mod error;
pub mod grain;
pub mod needs;
pub mod param;
pub mod registry;
pub mod rng;
pub mod runtime;
pub mod scene;

pub use closure::drag::DragLaw;
pub use closure::fluctuation::{
    DriftForm, FlowScales, Fluctuation, FluctuationDraw, ParticleSlip, SlipReynolds, TurbulencePoint,
};
pub use closure::granular::{
    Grains, GranularStress, JohnsonJacksonElastic, KineticCoefficients, KineticTheory, LocalRheology, LocalState,
    SaltationInput,
};
pub use closure::hindrance::{DragReynolds, Hindrance};
pub use closure::turbulence::{ColumnView, Turbulence};
pub use closure::viscosity::EffectiveViscosity;
pub use closure::wall_friction::WallFriction;
pub use closure::Family;
pub use error::{Error, Result};
pub use needs::{Field, Needs};
pub use param::{Bound, Choice, Describe, DescribeField, Limit, Param, ParamError, ParamRange, ParamSet};
pub use registry::ModelEntry;
/// `#[derive(Describe)]` and `#[derive(Params)]`: see [`saltus_derive`].
pub use saltus_derive::{Describe, Params};

/// Re-exported so that `register_model!` works from crates that do not depend on inventory.
pub use inventory;

/// Standard gravity used by every scene unless it overrides `physics.gravity` (m/s^2).
pub const G: f64 = 9.81;
