//! `saltus._native`: the Rust side of the `saltus` Python package.
//!
//! Thin bindings over the `saltus` library crate, so that Python and the command line share
//! one scene loader (with the `--set` overrides), one run driver, one closure evaluator and
//! one model listing: nothing here computes physics, and no input is read twice. The
//! Python-facing API, with its documentation, is the `saltus` package (`python/saltus/`);
//! this crate converts values and errors:
//!
//! - `convert`: Python values as TOML values and overrides, JSON and TOML values as Python
//!   values;
//! - `errors`: the `SceneError` and `RunError` exceptions and the saltus errors raised as
//!   them;
//! - `commands`: `check`, `run`, `compare`, `diagnose`, `models`; `calibrate` and `sweep`
//!   in their own files;
//! - `closure_eval`: the `Closure` class;
//! - `closures`: closures written in Python, registered and checked.
//!
//! Closures written in Python (`saltus.register_closure`, module `closures`) take the
//! contract of the `Closure` class: named arrays in, named arrays out.

// saltus_core::Error carries file, key and message; it is built once per failed call,
// never in a hot loop, so its size does not matter (as in saltus-solvers).
#![allow(clippy::result_large_err)]

use pyo3::exceptions::PyImportError;
use pyo3::prelude::*;

mod calibrate;
mod closure_eval;
mod closures;
mod commands;
mod convert;
mod declarations;
mod errors;
mod seeds;
mod sweep;

/// The native module `saltus._native`.
#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    saltus::ensure_registry().map_err(|e| PyImportError::new_err(format!("{e:#}")))?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("RunError", py.get_type::<errors::RunError>())?;
    m.add_function(wrap_pyfunction!(commands::check, m)?)?;
    m.add_function(wrap_pyfunction!(commands::run, m)?)?;
    m.add_function(wrap_pyfunction!(seeds::run_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(commands::compare, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate, m)?)?;
    m.add_class::<calibrate::Misfit>()?;
    m.add_function(wrap_pyfunction!(commands::models, m)?)?;
    m.add_function(wrap_pyfunction!(commands::diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_prepare, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_collect, m)?)?;
    m.add_class::<closure_eval::Closure>()?;
    m.add_function(wrap_pyfunction!(closures::register_closure, m)?)?;
    m.add_function(wrap_pyfunction!(closures::unregister_closure, m)?)?;
    m.add_function(wrap_pyfunction!(closures::register_faces, m)?)?;
    m.add_function(wrap_pyfunction!(commands::scene_modules, m)?)?;
    m.add_function(wrap_pyfunction!(commands::cli_main, m)?)?;
    // this process imports a scene's [python] modules (saltus.run, python -m saltus)
    saltus_core::runtime::set_python_host();
    m.add_function(wrap_pyfunction!(closure_eval::closure_check, m)?)?;
    Ok(())
}
