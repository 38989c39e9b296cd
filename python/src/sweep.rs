//! `saltus.sweep`: the sweep file loaded, checked and written out point by point for the
//! caller's executor, then its points gathered into the table the command line writes.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use saltus::sweep;

use crate::convert::{overrides, toml_to_py};
use crate::errors::SceneError;

fn sweep_error(e: anyhow::Error) -> PyErr {
    SceneError::new_err(saltus::describe(&e))
}

/// Load and check the sweep `file` (with the overrides `set`), write one resolved scene
/// per point into `out` (default `out/<meta.name>`) with the manifest, and return the
/// folder and the points as dicts: `index`,
/// `scene` (the file), `dir` (its output folder), `finished` (with `resume`, a point
/// whose summary says it finished).
#[pyfunction]
#[pyo3(signature = (file, set, out, resume))]
pub fn sweep_prepare<'py>(
    py: Python<'py>,
    file: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    resume: bool,
) -> PyResult<(String, Bound<'py, PyList>)> {
    let set = overrides(set)?;
    let (out, points) = py
        .detach(|| {
            let s = sweep::load(&file, &set)?;
            let out = out.unwrap_or_else(|| sweep::default_out(&s));
            sweep::prepare(&s, &out, resume).map(|p| (out, p))
        })
        .map_err(sweep_error)?;
    let list = PyList::empty(py);
    for p in points {
        let d = PyDict::new(py);
        d.set_item("index", p.index)?;
        d.set_item("scene", p.scene.display().to_string())?;
        d.set_item("dir", p.dir.display().to_string())?;
        d.set_item("finished", p.finished)?;
        list.append(d)?;
    }
    Ok((out.display().to_string(), list))
}

/// Gather the points run in `out` into `sweep.csv` (and `sweep_seeds.csv`, the figure),
/// and return the table: `name`, `combine`, `axes` (key, name, values, labels),
/// `header`, `rows` (strings, as in the CSV), `files`, `fits` (one per series of the
/// figure, with its `series` label) and `warnings`.
#[pyfunction]
#[pyo3(signature = (file, set, out))]
pub fn sweep_collect<'py>(
    py: Python<'py>,
    file: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let report = py.detach(|| sweep::load(&file, &set).and_then(|s| sweep::collect(&s, &out))).map_err(sweep_error)?;
    let (header, rows) = sweep::table::rows(&report.manifest, &report.summaries);
    let d = PyDict::new(py);
    d.set_item("name", &report.manifest.name)?;
    d.set_item(
        "combine",
        match report.manifest.combine {
            sweep::spec::Combine::Product => "product",
            sweep::spec::Combine::Zip => "zip",
        },
    )?;
    let axes = PyList::empty(py);
    for a in &report.manifest.axes {
        let x = PyDict::new(py);
        x.set_item("key", &a.key)?;
        x.set_item("name", &a.name)?;
        x.set_item("values", toml_to_py(py, &toml::Value::Array(a.values.clone()))?)?;
        x.set_item("labels", &a.labels)?;
        axes.append(x)?;
    }
    d.set_item("axes", axes)?;
    d.set_item("header", header)?;
    d.set_item("rows", rows)?;
    d.set_item("files", report.files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>())?;
    let fits = PyList::empty(py);
    for (label, f) in &report.fits {
        {
            let x = PyDict::new(py);
            x.set_item("series", label)?;
            x.set_item("a", f.a)?;
            x.set_item("a_stderr", f.a_stderr)?;
            x.set_item("theta_c", f.theta_c)?;
            x.set_item("theta_c_stderr", f.theta_c_stderr)?;
            x.set_item("n", f.n)?;
            x.set_item("rms", f.rms)?;
            x.set_item("at_bound", f.at_bound)?;
            x.set_item("n_stand_in", f.n_stand_in)?;
            fits.append(x)?;
        }
    }
    d.set_item("fits", fits)?;
    d.set_item("warnings", &report.warnings)?;
    Ok(d)
}
