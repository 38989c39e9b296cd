//! The command line's commands as functions of `saltus._native`: `check`, `run`, `compare`,
//! `diagnose` and `models`, each taking the command's arguments and returning what it
//! printed and wrote as Python values; the `[python]` modules of a scene; and the whole
//! command line in this process (`python -m saltus`).

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use numpy::PyArray1;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use saltus::{listing, runner};
use saltus_core::scene::Scene;
use saltus_solvers::Progress;

use crate::convert::{json_to_py, overrides, toml_to_py};
use crate::errors::{load_error, run_error, Place, RunError, SceneError};

/// Wall time between two looks at Python's pending signals during a run: Ctrl-C stops a
/// run within this, and the GIL is taken five times a second, not once a step.
pub(crate) const SIGNAL_CHECK_EVERY: Duration = Duration::from_millis(200);

/// `saltus check`: the scene loaded with the overrides and checked whole, as (dict, TOML
/// text of the resolved scene).
#[pyfunction]
#[pyo3(signature = (scene, set=None, closures=None))]
pub fn check<'py>(
    py: Python<'py>,
    scene: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    closures: Option<PathBuf>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let set = overrides(set)?;
    let s = py.detach(|| runner::load_checked(&scene, &set, closures.as_deref())).map_err(|e| load_error(py, e))?;
    let text = s.to_toml().map_err(|e| load_error(py, e))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| PyRuntimeError::new_err(format!("resolved scene does not read back: {e}")))?;
    Ok((toml_to_py(py, &toml::Value::Table(table))?, text))
}

/// `saltus run`: load the scene with the overrides, run it into `out` (default: the
/// scene's `output.dir`, else `out/<meta.name>`) with the GIL released, and return the
/// last state as a dict. A Python signal (Ctrl-C) stops the run through its observer; the
/// outputs are written and the exception the signal handler raised is returned under
/// `interrupt`, for the caller to raise.
#[pyfunction]
// the arguments are Python's keyword arguments of `saltus.run`, one per option of `saltus run`
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, set=None, out=None, quiet=true, restart=None, closures=None, warm_start=None))]
pub fn run<'py>(
    py: Python<'py>,
    scene: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    quiet: bool,
    restart: Option<PathBuf>,
    closures: Option<PathBuf>,
    warm_start: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let s = py
        .detach(|| Scene::from_file_with_closures(&scene, &set, closures.as_deref()))
        .map_err(|e| load_error(py, e))?;
    if let (Some(_), Some(from)) = (&restart, &warm_start) {
        return Err(SceneError::new_err(format!(
            "warm_start {}: a continued run (restart) goes on from its own checkpoint",
            from.display()
        )));
    }
    let warm = match &warm_start {
        None => None,
        Some(from) => match runner::warm_state(&s, from) {
            Ok(Ok(w)) => Some(w),
            Ok(Err(why)) => return Err(SceneError::new_err(format!("warm_start {}: {why}", from.display()))),
            Err(e) => return Err(SceneError::new_err(format!("warm_start: {e:#}"))),
        },
    };
    let out = out.unwrap_or_else(|| runner::default_out(&s));
    let bar =
        if quiet { indicatif::ProgressBar::hidden() } else { runner::progress_bar(std::io::stderr().is_terminal()) };
    let mut interrupt: Option<PyErr> = None;
    let result = py.detach(|| {
        let mut last = Instant::now();
        let mut stop = |_: &Progress| {
            if interrupt.is_none() && last.elapsed() >= SIGNAL_CHECK_EVERY {
                last = Instant::now();
                interrupt = Python::attach(|py| py.check_signals()).err();
            }
            interrupt.is_some()
        };
        let settings = runner::RunSettings {
            restart: restart.clone(),
            log_every: (!quiet).then(|| std::time::Duration::from_secs_f64(runner::LOG_INTERVAL)),
            max_wall: None,
            warm_start: warm.clone(),
        };
        runner::run_scene_with(&s, &out, &bar, &settings, &mut stop)
    });
    // a closure written in Python that raised (or returned something unusable) during the
    // run: its message, whatever the solver made of the NaN it got
    if let Some(f) = s.closures.failure() {
        // the message starts with the closure's family: its table is the key
        let family = f.split_whitespace().next().and_then(saltus_core::closure::Family::from_key);
        let key = family.map(|fam| format!("closures.{fam}"));
        let place = Place { file: Some(scene.display().to_string()), key, io: false };
        return Err(place.attach(py, RunError::new_err(f)));
    }
    let outcome = result.map_err(|e| run_error(py, e))?;
    let (Some(ending), Some(report)) = (&outcome.ending, &outcome.report) else {
        return Err(RunError::new_err(outcome.error.clone().unwrap_or_else(|| "the run failed".into())));
    };
    let d = PyDict::new(py);
    d.set_item("ending", ending.name())?;
    // read back with Python's json, as a user reads summary.json: the file's key order
    let summary = serde_json::to_string(&report.summary).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    d.set_item("summary", py.import("json")?.call_method1("loads", (summary,))?)?;
    let profiles = PyDict::new(py);
    for (name, values) in &report.profiles.columns {
        profiles.set_item(name, PyArray1::from_slice(py, values))?;
    }
    d.set_item("profiles", profiles)?;
    d.set_item("text", &report.text)?;
    d.set_item("out", out.display().to_string())?;
    d.set_item("wall", outcome.wall)?;
    d.set_item("figure", outcome.figure.as_ref().map(|p| p.display().to_string()))?;
    d.set_item("warnings", &outcome.warnings)?;
    let breakdown = match ending.breakdown() {
        Some(b) => json_to_py(py, &serde_json::to_value(b).map_err(|e| PyRuntimeError::new_err(e.to_string()))?)?,
        None => py.None().into_bound(py),
    };
    d.set_item("breakdown", breakdown)?;
    d.set_item("scene_toml", s.to_toml().ok())?;
    d.set_item("interrupt", interrupt.map(|e| e.into_value(py)))?;
    Ok(d)
}

/// `saltus compare FILE`: every variant, the comparison table and, with a `[reference]`, the
/// work-precision table; the paths of what it wrote and its warnings.
#[pyfunction]
#[pyo3(signature = (file, set=None, out=None))]
pub fn compare<'py>(
    py: Python<'py>,
    file: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let cmp =
        py.detach(|| saltus::compare::load(&file, &set)).map_err(|e| SceneError::new_err(saltus::describe(&e)))?;
    let out = out.unwrap_or_else(|| saltus::compare::default_out(&cmp));
    let report =
        py.detach(|| saltus::compare::run(&cmp, &out, false)).map_err(|e| RunError::new_err(saltus::describe(&e)))?;
    let d = PyDict::new(py);
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    d.set_item("out", out.display().to_string())?;
    d.set_item("table", report.table.display().to_string())?;
    d.set_item("figure", path(&report.figure))?;
    d.set_item("precision", path(&report.precision_table))?;
    d.set_item("precision_figure", path(&report.precision_figure))?;
    d.set_item("failures", report.failures())?;
    d.set_item("warnings", &report.warnings)?;
    Ok(d)
}

/// `saltus diagnose`: the closures held against the run(s) in `dir` (and `pool`), the
/// files written into `out` (default `dir/diagnose`), and with `fit` the fits, as a dict:
/// `text` (the printed table), `out`, `files`, `warnings`, `fits` (see
/// `saltus::diagnose::Diagnosis::fits_json`), `fitted` (the fitted.toml written, or None).
#[pyfunction]
#[pyo3(signature = (dir, closures, phi_min, fit, z_min, z_max, out, pool))]
#[allow(clippy::too_many_arguments)]
pub fn diagnose<'py>(
    py: Python<'py>,
    dir: PathBuf,
    closures: Vec<String>,
    phi_min: f64,
    fit: bool,
    z_min: Option<f64>,
    z_max: Option<f64>,
    out: Option<PathBuf>,
    pool: Vec<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let opts = saltus::diagnose::Options { phi_min, fit, window: saltus::diagnose::Window { z_min, z_max } };
    let dirs: Vec<PathBuf> = std::iter::once(dir.clone()).chain(pool).collect();
    let out = out.unwrap_or_else(|| dir.join("diagnose"));
    let done = py.detach(|| -> anyhow::Result<_> {
        let d = saltus::diagnose::diagnose_pooled(&dirs, &closures, opts)?;
        let written = d.write(&out)?;
        Ok((d, written))
    });
    let (d, written) = done.map_err(|e| SceneError::new_err(format!("{e:#}")))?;
    let fitted = out.join(saltus::diagnose::FITTED);
    let value = serde_json::json!({
        "text": d.text(),
        "out": out.display().to_string(),
        "files": written.files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>(),
        "warnings": written.warnings,
        "fits": if fit { d.fits_json() } else { serde_json::Value::Null },
        "fitted": written.files.contains(&fitted).then(|| fitted.display().to_string()),
    });
    json_to_py(py, &value)
}

/// `saltus models --json`: every registered model (of one family when given).
#[pyfunction]
#[pyo3(signature = (family=None))]
pub fn models<'py>(py: Python<'py>, family: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    let family = family.map(listing::parse_family).transpose().map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    json_to_py(py, &listing::json(family))
}

/// The `[python] modules` of a scene with its overrides (files absolute), for the Python
/// package to import before it loads the scene.
#[pyfunction]
#[pyo3(signature = (scene, set=None))]
pub fn scene_modules(
    py: Python<'_>,
    scene: std::path::PathBuf,
    set: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<String>> {
    let set = crate::convert::overrides(set)?;
    saltus_core::scene::Scene::python_modules(&scene, &set).map_err(|e| crate::errors::load_error(py, e))
}

/// The command line on `args` (the program name first) in this process, with the GIL
/// released (the DEM calls Python closures from its threads): its exit code.
#[pyfunction]
pub fn cli_main(py: Python<'_>, args: Vec<String>) -> u8 {
    let args = args.into_iter().map(std::ffi::OsString::from).collect();
    py.detach(|| saltus::cli::main_from(args))
}
