//! The `Closure` class: one closure model of a `saltus closure eval` family, built from its
//! table and evaluated on arrays; and `saltus.closure_check`, the command line's property
//! checks of any closure model.

use std::path::Path;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use saltus::check::{self, Options};
use saltus::eval::{self, EvalFamily, Model, Rows};
use saltus::listing;
use saltus::table::Table;
use saltus_core::Error;

use crate::declarations::family_of;

use crate::convert::{json_to_py, py_to_toml};
use crate::errors::{Place, SceneError};

/// Label of closure errors, in place of the command line's `--model`.
const CLOSURE: &str = "saltus.Closure";

/// One closure of a `saltus closure eval` family, built and range-checked once.
#[pyclass(module = "saltus._native", frozen)]
pub struct Closure {
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

/// `saltus.closure_check`: `saltus closure check --family F --model TOML`, as a dict.
#[pyfunction]
#[pyo3(signature = (family, model, cases=256))]
pub fn closure_check<'py>(
    py: Python<'py>,
    family: &str,
    model: &Bound<'py, PyAny>,
    cases: u32,
) -> PyResult<Bound<'py, PyAny>> {
    let fam = family_of(family)?;
    let scene_error = |e: anyhow::Error| SceneError::new_err(saltus::describe(&e));
    let value = if let Ok(text) = model.cast::<PyString>() {
        check::parse_model(&text.to_cow()?).map_err(scene_error)?
    } else if model.is_instance_of::<PyDict>() {
        py_to_toml(model, "model")?
    } else {
        return Err(PyTypeError::new_err("model: expected a dict or a TOML string"));
    };
    let report = py.detach(|| check::check(fam, value, Options { cases })).map_err(scene_error)?;
    let outcomes: Vec<serde_json::Value> = report
        .outcomes
        .iter()
        .map(|o| serde_json::json!({"name": o.name, "passed": o.passed, "summary": o.summary, "input": o.input}))
        .collect();
    let d = serde_json::json!({
        "family": report.family.key(),
        "model": report.model,
        "passed": report.passed(),
        "text": report.text(),
        "outcomes": outcomes,
    });
    json_to_py(py, &d)
}
