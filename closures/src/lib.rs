//! # saltus-closures
//!
//! Every closure model of saltus, one file per model, grouped by family. Each model is a
//! plain `Serialize + Deserialize` struct registered twice: with typetag (so a scene can
//! name it by `type`) and with [`saltus_core::register_model!`] (so `saltus models` lists
//! it and the registry tests see it).
//!
//! Binaries that never name this crate lose its registrations at link time; call
//! [`link`] once at start-up (the `saltus` program does).

pub mod drag;
pub mod fluctuation;
pub mod granular;
pub mod hindrance;
pub mod runtime;
pub mod turbulence;
pub mod viscosity;
pub mod wall_friction;

#[cfg(test)]
pub(crate) mod testing;

/// Force the linker to keep this crate's registrations; returns the number of registered
/// models (all crates included).
pub fn link() -> usize {
    saltus_core::registry::models().len()
}
