//! `saltus run --seeds N` as a function of `saltus._native`: the seeds of a DEM scene run
//! in parallel as one answer, with the GIL released and Python's signals watched.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use pyo3::prelude::*;
use pyo3::types::PyDict;
use saltus::{runner, seeds};
use saltus_core::scene::Scene;

use crate::commands::SIGNAL_CHECK_EVERY;
use crate::convert::overrides;
use crate::errors::{load_error, RunError, SceneError};

/// `saltus run SCENE --seeds N`: `seeds` seeds from the scene's, each in `out/seed_<k>/`,
/// stopped together by the scene's `solver.lagrangian.target_error` on their pooled
/// transport rate, and `out/seeds.json`. `warm_start` is the folder of one developed state
/// (every seed starts from it) or of a run of several seeds (one state each). Returns the
/// paths, the paragraph and each seed's error; a Python signal (Ctrl-C) ends every seed
/// with its outputs written and comes back under `interrupt`.
#[pyfunction]
// the arguments are Python's keyword arguments of `saltus.run_seeds`
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, seeds, set=None, out=None, quiet=true, closures=None, warm_start=None))]
pub fn run_seeds<'py>(
    py: Python<'py>,
    scene: PathBuf,
    seeds: usize,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    quiet: bool,
    closures: Option<PathBuf>,
    warm_start: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let base = py
        .detach(|| Scene::from_file_with_closures(&scene, &set, closures.as_deref()))
        .map_err(|e| load_error(py, e))?;
    let starts = py
        .detach(|| seeds::warm_starts(&base, warm_start.as_deref()))
        .map_err(|e| SceneError::new_err(format!("{e:#}")))?;
    let settings = runner::RunSettings { restart: None, log_every: None, max_wall: None, warm_start: starts.single };
    let out = out.unwrap_or_else(|| runner::default_out(&base));
    let stopped = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let stop = || stopped.load(Ordering::SeqCst);
    let (bank, stop, scene_ref, set_ref, out_ref, settings_ref) = (starts.bank, &stop, &scene, &set, &out, &settings);
    let closures_ref = closures.as_deref();
    let result = py.detach(|| {
        std::thread::scope(|sc| {
            let run = sc.spawn(move || {
                seeds::run_seeds(scene_ref, set_ref, closures_ref, seeds, out_ref, settings_ref, bank, stop)
            });
            // only the main thread may look at Python's signals: it watches while the
            // seeds run on their own threads
            while !run.is_finished() {
                std::thread::sleep(SIGNAL_CHECK_EVERY);
                if interrupt.is_none() {
                    interrupt = Python::attach(|py| py.check_signals()).err();
                    if interrupt.is_some() {
                        stopped.store(true, Ordering::SeqCst);
                    }
                }
            }
            run.join().unwrap_or_else(|_| Err(anyhow::anyhow!("the seeds stopped on an internal error")))
        })
    });
    let report = result.map_err(|e| RunError::new_err(saltus::describe(&e)))?;
    let d = PyDict::new(py);
    d.set_item("file", report.file.display().to_string())?;
    d.set_item("out", out.display().to_string())?;
    d.set_item("text", report.text())?;
    let errors: Vec<(u64, String)> =
        report.runs.iter().filter_map(|r| r.outcome.error.clone().map(|e| (r.seed, e))).collect();
    d.set_item("errors", errors)?;
    d.set_item("interrupt", interrupt.map(|e| e.into_value(py)))?;
    if !quiet {
        println!("{}\noutputs: {}", report.text(), report.file.display());
    }
    Ok(d)
}
