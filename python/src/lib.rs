//! `saltus._native`: the Rust side of the `saltus` Python package.
//!
//! Thin bindings over the `saltus` library crate, so that Python and the command line share
//! one scene loader (with the `--set` overrides), one run driver, one closure evaluator and
//! one model listing: nothing here computes physics, and no input is read twice. The
//! Python-facing API, with its documentation, is `python/saltus/__init__.py`; this module
//! converts values and errors.
//!
//! Closures written in Python (`saltus.register_closure`, module `closures`) take the
//! contract of the `Closure` class: named arrays in, named arrays out.

// saltus_core::Error carries file, key and message; it is built once per failed call,
// never in a hot loop, so its size does not matter (as in saltus-solvers).
#![allow(clippy::result_large_err)]

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::{PyImportError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use pyo3::IntoPyObjectExt;
use saltus::eval::{self, EvalFamily, Model, Rows};
use saltus::table::Table;
use saltus::{listing, runner};
use saltus_core::scene::Scene;
use saltus_core::Error;
use saltus_solvers::Progress;

mod calibrate;
mod closures;
mod sweep;

create_exception!(
    saltus,
    SceneError,
    PyValueError,
    "Bad input: a scene or closure table that does not load (TOML syntax, unknown key or \
     model, out-of-range value, unmet closure need, a scene its solver cannot start on). The \
     message is the command line's; `file` and `key` name the file and the key path when \
     the error has them (else None)."
);
create_exception!(
    saltus,
    RunError,
    PyRuntimeError,
    "A run that could not write its outputs (the output folder cannot be made or a file \
     cannot be written); `file` names it."
);

/// Wall time between two looks at Python's pending signals during a run: Ctrl-C stops a
/// run within this, and the GIL is taken five times a second, not once a step.
const SIGNAL_CHECK_EVERY: Duration = Duration::from_millis(200);

/// Label of closure errors, in place of the command line's `--model`.
const CLOSURE: &str = "saltus.Closure";

/// Where an error points: its file and key path, when it has them.
struct Place {
    file: Option<String>,
    key: Option<String>,
    /// a file that could not be read or written
    io: bool,
}

impl Place {
    fn of(e: &Error) -> Self {
        let (file, key): (Option<&Path>, Option<&str>) = match e {
            Error::Io { file, .. } | Error::Syntax { file, .. } => (Some(file), None),
            Error::Key { file, key, .. }
            | Error::UnknownModel { file, key, .. }
            | Error::OutOfRange { file, key, .. }
            | Error::UnmetNeed { file, key, .. } => (Some(file), Some(key)),
            Error::Invalid(_) => (None, None),
        };
        Place {
            file: file.map(|f| f.display().to_string()),
            key: key.map(str::to_string),
            io: matches!(e, Error::Io { .. }),
        }
    }

    /// `err` with this place as its `file` and `key` attributes.
    fn attach(self, py: Python<'_>, err: PyErr) -> PyErr {
        let value = err.value(py);
        // the attributes are extras: failing to set them must not hide the error itself
        let _ = value.setattr("file", self.file);
        let _ = value.setattr("key", self.key);
        err
    }
}

/// A scene that does not load (an unreadable scene file included: bad input, not a failed
/// output): [`SceneError`] with the message `saltus check` and `saltus run` print, the
/// error and its causes joined as anyhow's `{:#}` does.
fn load_error(py: Python<'_>, e: Error) -> PyErr {
    let place = Place::of(&e);
    let message = saltus::describe(&anyhow::Error::from(e));
    place.attach(py, SceneError::new_err(message))
}

/// A run that failed: [`RunError`] when its outputs could not be written, [`SceneError`]
/// when the solver could not be set up on the scene; the message `saltus run` prints.
fn run_error(py: Python<'_>, e: Error) -> PyErr {
    let place = Place::of(&e);
    let message = e.to_string();
    let err = if place.io { RunError::new_err(message) } else { SceneError::new_err(message) };
    place.attach(py, err)
}

/// A Python value as the TOML value it stands for: bool, int, float, str, dict (string
/// keys), list or tuple, and objects with `__index__` or `__float__` (numpy scalars).
/// `what` names the value in errors.
fn py_to_toml(v: &Bound<'_, PyAny>, what: &str) -> PyResult<toml::Value> {
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        let i: i64 =
            v.extract().map_err(|_| PyValueError::new_err(format!("{what}: integer {v} does not fit in 64 bits")))?;
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(toml::Value::String(s.to_cow()?.into_owned()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, x) in d.iter() {
            let k: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{what}: table keys must be strings, found {k}")))?;
            let inner = py_to_toml(&x, &format!("{what}.{k}"))?;
            t.insert(k, inner);
        }
        return Ok(toml::Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .enumerate()
            .map(|(i, x)| py_to_toml(&x?, &format!("{what}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if v.hasattr("__index__")? {
        if let Ok(i) = v.call_method0("__index__").and_then(|i| i.extract::<i64>()) {
            return Ok(toml::Value::Integer(i));
        }
    }
    if v.hasattr("__float__")? {
        return Ok(toml::Value::Float(v.call_method0("__float__")?.extract()?));
    }
    let ty = v.get_type().name().map_or_else(|_| "?".to_string(), |n| n.to_string());
    Err(PyTypeError::new_err(format!("{what}: a {ty} has no TOML form; use a bool, int, float, str, dict or list")))
}

/// The overrides of `set` as the command line's `KEY=VALUE` strings: a dict's values are
/// Python values written as TOML (so the command line's `apply_override` reads them back,
/// the one override code), an iterable of strings is taken as written.
fn overrides(set: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    let Some(set) = set.filter(|s| !s.is_none()) else {
        return Ok(Vec::new());
    };
    if let Ok(d) = set.cast::<PyDict>() {
        let mut out = Vec::with_capacity(d.len());
        for (k, v) in d.iter() {
            let key: String =
                k.extract().map_err(|_| PyTypeError::new_err(format!("set: keys must be strings, found {k}")))?;
            let value = py_to_toml(&v, &format!("set[{key:?}]"))?;
            out.push(format!("{key}={value}"));
        }
        return Ok(out);
    }
    if set.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err("set: expected a dict of key -> value or a list of \"KEY=VALUE\" strings"));
    }
    set.try_iter()
        .map_err(|_| PyTypeError::new_err("set: expected a dict of key -> value or a list of \"KEY=VALUE\" strings"))?
        .map(|s| {
            s?.extract::<String>().map_err(|_| PyTypeError::new_err("set: list items must be \"KEY=VALUE\" strings"))
        })
        .collect()
}

fn json_to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value as J;
    Ok(match v {
        J::Null => py.None().into_bound(py),
        J::Bool(b) => b.into_bound_py_any(py)?,
        J::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_bound_py_any(py)?,
            (None, Some(u)) => u.into_bound_py_any(py)?,
            _ => n.as_f64().unwrap_or(f64::NAN).into_bound_py_any(py)?,
        },
        J::String(s) => s.into_bound_py_any(py)?,
        J::Array(a) => PyList::new(py, a.iter().map(|x| json_to_py(py, x)).collect::<PyResult<Vec<_>>>()?)?.into_any(),
        J::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, json_to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

fn toml_to_py<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    use toml::Value as T;
    Ok(match v {
        T::String(s) => s.into_bound_py_any(py)?,
        T::Integer(i) => i.into_bound_py_any(py)?,
        T::Float(f) => f.into_bound_py_any(py)?,
        T::Boolean(b) => b.into_bound_py_any(py)?,
        T::Datetime(d) => d.to_string().into_bound_py_any(py)?,
        T::Array(a) => PyList::new(py, a.iter().map(|x| toml_to_py(py, x)).collect::<PyResult<Vec<_>>>()?)?.into_any(),
        T::Table(t) => {
            let d = PyDict::new(py);
            for (k, x) in t {
                d.set_item(k, toml_to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

/// `saltus check`: the scene loaded with the overrides and checked whole, as (dict, TOML
/// text of the resolved scene).
#[pyfunction]
#[pyo3(signature = (scene, set=None, closures=None))]
fn check<'py>(
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
#[pyo3(signature = (scene, set=None, out=None, quiet=true, restart=None, closures=None))]
fn run<'py>(
    py: Python<'py>,
    scene: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    quiet: bool,
    restart: Option<PathBuf>,
    closures: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let s = py
        .detach(|| Scene::from_file_with_closures(&scene, &set, closures.as_deref()))
        .map_err(|e| load_error(py, e))?;
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
            warm_start: None,
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
fn compare<'py>(
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
fn diagnose<'py>(
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
fn models<'py>(py: Python<'py>, family: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    let family = family.map(listing::parse_family).transpose().map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    json_to_py(py, &listing::json(family))
}

/// One closure of a `saltus closure eval` family, built and range-checked once.
#[pyclass(module = "saltus._native", frozen)]
struct Closure {
    model: Model,
}

#[pymethods]
impl Closure {
    /// `family` as `saltus closure eval --family`; `model` its table, a dict or TOML text.
    #[new]
    fn new(py: Python<'_>, family: &str, model: &Bound<'_, PyAny>) -> PyResult<Self> {
        let fam = EvalFamily::from_key(family).map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
        let value = if let Ok(text) = model.cast::<PyString>() {
            eval::parse_model_from(&text.to_cow()?, fam, CLOSURE).map_err(|e| SceneError::new_err(format!("{e:#}")))?
        } else if let Ok(d) = model.cast::<PyDict>() {
            match py_to_toml(d.as_any(), "model")? {
                toml::Value::Table(t) => eval::model_table(t, fam),
                _ => return Err(PyTypeError::new_err("model: expected a dict")),
            }
        } else {
            return Err(PyTypeError::new_err("model: expected a dict or a TOML string"));
        };
        let model = Model::build(fam, value, Path::new(CLOSURE), fam.key()).map_err(|e| {
            let place = e.downcast_ref::<Error>().map(Place::of);
            let err = SceneError::new_err(format!("{e:#}"));
            match place {
                Some(p) => p.attach(py, err),
                None => Place { file: Some(CLOSURE.into()), key: None, io: false }.attach(py, err),
            }
        })?;
        Ok(Closure { model })
    }

    /// The family, as given.
    #[getter]
    fn family(&self) -> &'static str {
        self.model.family().key()
    }

    /// The model's registered name.
    #[getter]
    fn name(&self) -> &'static str {
        self.model.describe().name()
    }

    /// Names the family reads.
    #[getter]
    fn input_names(&self) -> Vec<&'static str> {
        self.model.family().input_names().to_vec()
    }

    /// Names the family returns.
    #[getter]
    fn output_names(&self) -> Vec<&'static str> {
        self.model.family().outputs().to_vec()
    }

    /// The model as `saltus models --json` lists it, each parameter with its `value`.
    fn describe<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let d = self.model.describe();
        let default = self.model.registered_default();
        let entry = serde_json::json!({
            "family": self.model.family().key(),
            "name": d.name(),
            "equation": d.equation(),
            "source": d.source(),
            "parameters": listing::params_json(d, default.as_deref()),
        });
        json_to_py(py, &entry)
    }

    /// Evaluate on 1-D float64 arrays of one length (the Python wrapper broadcasts); the
    /// fluctuation draw of row i uses stream i of `seed`.
    fn evaluate_arrays<'py>(
        &self,
        py: Python<'py>,
        inputs: &Bound<'py, PyDict>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut table = Table::default();
        for (k, v) in inputs.iter() {
            let name: String = k.extract()?;
            let a: PyReadonlyArray1<'_, f64> = v.extract()?;
            let values = a.as_array().to_vec();
            if let Some((i, x)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(PyValueError::new_err(format!(
                    "Closure.evaluate: input `{name}`, row {i}: {x} is not a finite number"
                )));
            }
            if table.rows() != values.len() && !table.names.is_empty() {
                return Err(PyValueError::new_err(format!(
                    "Closure.evaluate: input `{name}` has {} rows, `{}` has {}",
                    values.len(),
                    table.names[0],
                    table.rows()
                )));
            }
            table.push(name, values);
        }
        let outputs = py
            .detach(|| self.model.outputs(&table, Rows { origin: "Closure.evaluate", first: 0 }, seed))
            .map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
        let d = PyDict::new(py);
        for (name, values) in outputs.names.into_iter().zip(outputs.columns) {
            d.set_item(name, PyArray1::from_vec(py, values))?;
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!("Closure({:?}, {:?})", self.model.family().key(), self.model.describe().name())
    }
}

/// The native module `saltus._native`.
#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    saltus::ensure_registry().map_err(|e| PyImportError::new_err(format!("{e:#}")))?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("RunError", py.get_type::<RunError>())?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate, m)?)?;
    m.add_class::<calibrate::Misfit>()?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    m.add_function(wrap_pyfunction!(diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_prepare, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_collect, m)?)?;
    m.add_class::<Closure>()?;
    m.add_function(wrap_pyfunction!(closures::register_closure, m)?)?;
    m.add_function(wrap_pyfunction!(closures::unregister_closure, m)?)?;
    m.add_function(wrap_pyfunction!(closures::register_faces, m)?)?;
    m.add_function(wrap_pyfunction!(closures::scene_modules, m)?)?;
    m.add_function(wrap_pyfunction!(closures::cli_main, m)?)?;
    // this process imports a scene's [python] modules (saltus.run, python -m saltus)
    saltus_core::runtime::set_python_host();
    m.add_function(wrap_pyfunction!(closures::closure_check, m)?)?;
    Ok(())
}
