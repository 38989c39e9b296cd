//! `saltus calibrate` from Python: the calibration run in this process, its report as the
//! JSON it wrote.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::overrides;
use crate::errors::{RunError, SceneError};

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

/// A calibrate file's misfit as a function of its free constants, for samplers that need
/// chi^2 at points of their choosing (the posterior of docs/calibration.md). Each call
/// runs the model once, warm from the anchor's state, and releases the GIL while it runs,
/// so that a thread pool evaluates several points at once; the value at a point does not
/// depend on the order of the calls.
#[pyclass(module = "saltus._native", frozen)]
pub struct Misfit {
    problem: saltus::calibrate::Problem,
}

impl Misfit {
    fn checked(&self, params: &[f64]) -> PyResult<()> {
        let keys = &self.problem.cal.parameters;
        if params.len() != keys.len() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "params: {} values for the {} free constants {:?}",
                params.len(),
                keys.len(),
                keys.iter().map(|p| p.key.as_str()).collect::<Vec<_>>()
            )));
        }
        if let Some((p, v)) = keys.iter().zip(params).find(|(_, v)| !v.is_finite()) {
            return Err(pyo3::exceptions::PyValueError::new_err(format!("params: `{}` = {v} is not finite", p.key)));
        }
        Ok(())
    }
}

#[pymethods]
impl Misfit {
    /// Load `file` (and `set`, as `saltus.calibrate`'s), its base scene and its reference.
    #[new]
    #[pyo3(signature = (file, set=None))]
    fn new(py: Python<'_>, file: PathBuf, set: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let set = overrides(set)?;
        let problem = py
            .detach(|| saltus::calibrate::load(&file, &set).and_then(saltus::calibrate::Problem::new))
            .map_err(|e| SceneError::new_err(saltus::describe(&e)))?;
        Ok(Misfit { problem })
    }

    /// The free constants' keys, in the file's order.
    #[getter]
    fn keys(&self) -> Vec<String> {
        self.problem.cal.parameters.iter().map(|p| p.key.clone()).collect()
    }

    /// Each constant's `[low, high]`.
    #[getter]
    fn bounds(&self) -> Vec<[f64; 2]> {
        self.problem.cal.parameters.iter().map(|p| p.bounds).collect()
    }

    /// The start values (the file's `start` or the base scene's).
    #[getter]
    fn start(&self) -> Vec<f64> {
        self.problem.start.clone()
    }

    /// Make the state of the run at `params` the start of every later call.
    fn anchor(&self, py: Python<'_>, params: Vec<f64>) -> PyResult<()> {
        self.checked(&params)?;
        py.detach(|| self.problem.anchor(&params));
        Ok(())
    }

    /// chi^2 at `params` (the sum calibrate minimises with unit weights: the statistical
    /// model's, priors included); +inf outside the bounds and where the run fails or gives
    /// no finite misfit, so that a sampler rejects the point.
    fn chi2(&self, py: Python<'_>, params: Vec<f64>) -> PyResult<f64> {
        self.checked(&params)?;
        let inside = self.problem.cal.parameters.iter().zip(&params).all(|(p, v)| *v > p.bounds[0] && *v < p.bounds[1]);
        if !inside {
            return Ok(f64::INFINITY);
        }
        let chi2 = py.detach(|| {
            let report = self.problem.run(&params).ok()?;
            self.problem.fit(&params, &report).map(|f| f.chi2)
        });
        Ok(chi2.filter(|c| c.is_finite()).unwrap_or(f64::INFINITY))
    }
}
