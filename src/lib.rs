//! The `saltus` command-line program's library: closure listing, evaluation of one closure
//! on a CSV, closure comparison plots, the run driver and scene comparisons. No physics
//! lives here: every number comes from a closure or a solver.

pub mod compare;
pub mod errors;
pub mod eval;
pub mod listing;
pub mod plot;
pub mod runner;
pub mod table;

/// Make sure the closure registrations are linked into this binary, and that they are
/// not empty.
pub fn ensure_registry() -> anyhow::Result<usize> {
    let n = saltus_closures::link();
    if n == 0 {
        anyhow::bail!("no closure model is registered: the closures crate was not linked");
    }
    Ok(n)
}
