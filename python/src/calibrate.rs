//! `saltus calibrate` from Python: the calibration run in this process, its report as the
//! JSON it wrote.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{overrides, RunError, SceneError};

/// `saltus calibrate FILE`: with `check`, the file checked as a run would and a line of
/// what it would fit; else the calibration run into `out` (default `out/<meta.name>`),
/// returning `out`, `files`, `warnings`, `text` (the printed summary) and `json` (the
/// path of calibration.json).
#[pyfunction]
#[pyo3(signature = (file, set=None, out=None, check=false))]
pub fn calibrate<'py>(
    py: Python<'py>,
    file: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    check: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let set = overrides(set)?;
    let scene_error = |e: anyhow::Error| SceneError::new_err(saltus::describe(&e));
    let cal = py.detach(|| saltus::calibrate::load(&file, &set)).map_err(scene_error)?;
    let d = PyDict::new(py);
    if check {
        let text = py.detach(|| saltus::calibrate::check(cal)).map_err(scene_error)?;
        d.set_item("text", text)?;
        return Ok(d);
    }
    let out = out.unwrap_or_else(|| saltus::calibrate::default_out(&cal));
    let report = py.detach(|| saltus::calibrate::run(cal, &out)).map_err(|e| {
        // a file the checks refuse is a scene error, a failed model run a run error
        let message = saltus::describe(&e);
        if e.downcast_ref::<saltus_core::Error>().is_some() {
            SceneError::new_err(message)
        } else {
            RunError::new_err(message)
        }
    })?;
    d.set_item("out", out.display().to_string())?;
    d.set_item("files", report.files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>())?;
    d.set_item("warnings", &report.warnings)?;
    d.set_item("text", report.text())?;
    d.set_item("json", out.join(saltus::calibrate::JSON).display().to_string())?;
    Ok(d)
}
