//! Closure families: one trait per family, object-safe, `Send + Sync`, (de)serialised with
//! `#[typetag::serde(tag = "type")]` so that a scene names a model by its `type`.
//!
//! Every family has scalar methods and batch methods over slices whose default loops over
//! the scalar one; a batch call through `Box<dyn Family>` is one virtual call per column or
//! particle array, and the default loop is monomorphised per model.

pub mod drag;
pub mod fluctuation;
pub mod granular;
pub mod hindrance;
pub mod turbulence;
pub mod viscosity;
pub mod wall_friction;

use std::fmt;

/// The closure families, in the order of the scene's `[closures]` tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// single-particle drag coefficient C_D(Re_p), `[closures.drag]`
    Drag,
    /// hindrance factor f(phi, Re_p), `[closures.hindrance]`
    Hindrance,
    /// fluid effective viscosity nu_eff/nu_f, `[closures.viscosity]`
    Viscosity,
    /// granular stress (mu(I), mu(K), frictional-collisional), `[closures.granular]`
    Granular,
    /// turbulence (laminar, mixing length, ...), `[closures.turbulence]`
    Turbulence,
    /// fluid velocity fluctuations seen by particles, `[closures.fluctuation]`
    Fluctuation,
    /// friction of smooth side walls on the fluid of a narrow channel, `[closures.wall_friction]`
    WallFriction,
}

impl Family {
    /// Every family, in scene order.
    pub const ALL: [Family; 7] = [
        Family::Drag,
        Family::Hindrance,
        Family::Viscosity,
        Family::Granular,
        Family::Turbulence,
        Family::Fluctuation,
        Family::WallFriction,
    ];

    /// Key of the family's table under `[closures]`.
    pub fn key(self) -> &'static str {
        match self {
            Family::Drag => "drag",
            Family::Hindrance => "hindrance",
            Family::Viscosity => "viscosity",
            Family::Granular => "granular",
            Family::Turbulence => "turbulence",
            Family::Fluctuation => "fluctuation",
            Family::WallFriction => "wall_friction",
        }
    }

    /// Family from its table key.
    pub fn from_key(key: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.key() == key)
    }

    /// One-line description.
    pub fn describe(self) -> &'static str {
        match self {
            Family::Drag => "single-particle drag coefficient C_D(Re_p)",
            Family::Hindrance => "hindrance factor multiplying the single-particle drag force",
            Family::Viscosity => "fluid effective viscosity ratio nu_eff/nu_f(phi)",
            Family::Granular => "granular stress: local rheologies and frictional-collisional kinetic theory",
            Family::Turbulence => "turbulence closure: mixing length / eddy viscosity",
            Family::Fluctuation => "fluid velocity fluctuations seen by particles and their mean-field diffusivity",
            Family::WallFriction => "friction factor of smooth side walls on the fluid of a narrow channel",
        }
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}
