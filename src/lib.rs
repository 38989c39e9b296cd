//! The `saltus` command-line program's library, one module per command (closure listing,
//! evaluation of one closure on a CSV, closure plots, scene checks, the run driver, seed
//! ensembles, comparisons, sweeps, calibrations, diagnoses), the figures they all draw
//! ([`figures`]) and the reading of a run's folder ([`run_files`]). No physics lives here:
//! every number comes from a closure or a solver.

// Errors carry file, key and message for the user; they are built once per failed run,
// never in a hot loop, so their size does not matter (as in saltus-solvers).
#![allow(clippy::result_large_err)]
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

/// `e` with each of its causes once: an error whose text already ends with its cause's
/// (an I/O error that names its OS error and also chains it) does not repeat it, which
/// anyhow's `{:#}` would. A run of characters far longer than any key or path (a value
/// pasted by mistake) is cut ([`saltus_core::error::clip_words`]).
pub fn describe(e: &anyhow::Error) -> String {
    let mut s = e.to_string();
    for cause in e.chain().skip(1) {
        let t = cause.to_string();
        if !s.ends_with(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
    }
    saltus_core::error::clip_words(&s).into_owned()
}

pub mod args;
pub mod calibrate;
pub mod check;
pub mod cli;
pub mod compare;
pub mod diagnose;
pub mod eval;
pub mod figures;
pub mod least_squares;
pub mod listing;
pub mod plot;
pub mod run_files;
pub mod runner;
pub mod seeds;
pub mod study_file;
pub mod sweep;
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
