//! Python values as the TOML values and `--set` overrides the scene loader reads, and the
//! JSON and TOML values saltus returns as Python values.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use pyo3::IntoPyObjectExt;

/// A Python value as the TOML value it stands for: bool, int, float, str, dict (string
/// keys), list or tuple, and objects with `__index__` or `__float__` (numpy scalars).
/// `what` names the value in errors.
pub(crate) fn py_to_toml(v: &Bound<'_, PyAny>, what: &str) -> PyResult<toml::Value> {
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
pub(crate) fn overrides(set: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
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

/// A JSON value as a Python value: null as None, numbers as int or float, arrays as lists,
/// objects as dicts.
pub(crate) fn json_to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
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

/// A TOML value as a Python value: tables as dicts, arrays as lists, datetimes as their
/// TOML text.
pub(crate) fn toml_to_py<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
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
