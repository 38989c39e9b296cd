//! # saltus-solvers
//!
//! Solvers of saltus. The entry point [`run`] dispatches on the scene's `[solver] type`.
//! The Eulerian two-fluid solver and the Lagrangian DEM solver plug in here; until they
//! land, a scene that asks for one is refused with a clear message rather than a stub
//! result.

// Errors carry file, key and message for the user; they are built once per failed run,
// never in a hot loop, so their size does not matter.
#![allow(clippy::result_large_err)]

pub mod column;

use std::fmt;
use std::path::Path;

use saltus_core::scene::Scene;
use saltus_core::Error;

/// Solvers the program knows, with whether this build implements them.
pub const SOLVERS: [(&str, bool); 2] = [("eulerian", false), ("lagrangian", false)];

/// Short result of a run, printed by `saltus run`.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    /// one paragraph
    pub text: String,
}

impl fmt::Display for RunSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// Run `scene`, writing its outputs into `out`.
pub fn run(scene: &Scene, _out: &Path, _progress: bool) -> Result<RunSummary, Error> {
    let file = scene.path.display();
    let solver = scene.solver.as_ref().and_then(|t| t.get("type")).and_then(|v| v.as_str()).ok_or_else(|| {
        Error::Invalid(format!(
            "{file}: key `solver.type`: missing; known solvers: {}",
            SOLVERS.map(|s| s.0).join(", ")
        ))
    })?;
    match SOLVERS.iter().find(|s| s.0 == solver) {
        None => Err(Error::Invalid(format!(
            "{file}: key `solver.type`: unknown solver `{solver}`; known: {}",
            SOLVERS.map(|s| s.0).join(", ")
        ))),
        Some(_) => Err(Error::Invalid(format!(
            "{file}: solver `{solver}` is not implemented in this version yet; use `saltus check` and `saltus closure` meanwhile"
        ))),
    }
}
