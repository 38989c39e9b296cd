//! The `saltus` command-line program's library: closure listing, evaluation of one closure
//! on a CSV, closure comparison plots, the run driver and scene comparisons. No physics
//! lives here: every number comes from a closure or a solver.

// `src/main.rs` is also compiled inside this library (module `cli`) and names the library
// `saltus::...` as a binary would
extern crate self as saltus;

/// `eprintln!` that never panics: a closed or full stderr (`2>/dev/full`, errors piped
/// into `head`) loses the message, not the run's outputs or its exit code.
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

pub mod check;
pub mod cli;
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
