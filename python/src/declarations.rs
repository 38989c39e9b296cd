//! What a Python registration declares, read into the run-time registry's types: the
//! family's name, each `params=` entry (a default, or default, range, unit and
//! description), each `limits=` entry, all checked with an error naming the argument.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use saltus_core::closure::Family;
use saltus_core::param::{Bound as End, ParamRange};
use saltus_core::runtime::{self, Face, RuntimeLimit};
use saltus_core::{Limit, Param};

pub(crate) fn leak(s: String) -> &'static str {
    // a registration lives as long as the process; Describe hands its strings out as 'static
    Box::leak(s.into_boxed_str())
}

pub(crate) fn family_of(family: &str) -> PyResult<Family> {
    saltus::listing::parse_family(family).map_err(|e| PyValueError::new_err(format!("{e:#}")))
}

/// One `params=` entry: a default, or a dict of `default`, `range`, `unit`, `description`.
pub(crate) fn param(name: &str, v: &Bound<'_, PyAny>) -> PyResult<Param> {
    let what = format!("params[{name:?}]");
    let real = |x: &Bound<'_, PyAny>, key: &str| -> PyResult<f64> {
        x.extract::<f64>().map_err(|_| PyTypeError::new_err(format!("{what}{key}: expected a number, found {x}")))
    };
    let Ok(d) = v.cast::<PyDict>() else {
        return Ok(Param::new(name, real(v, "")?, ParamRange::any(), "", ""));
    };
    let mut p = Param::new(name, f64::NAN, ParamRange::any(), "", "");
    let mut has_default = false;
    for (k, x) in d.iter() {
        let k: String = k.extract()?;
        match k.as_str() {
            "default" => {
                p.value = real(&x, "[\"default\"]")?;
                has_default = true;
            }
            "range" => {
                p.range = if let Ok(s) = x.cast::<PyString>() {
                    s.to_cow()?.parse().map_err(|e: String| PyValueError::new_err(format!("{what}: {e}")))?
                } else {
                    let (lo, hi): (f64, f64) = x.extract().map_err(|_| {
                        PyTypeError::new_err(format!("{what}[\"range\"]: an interval \"(0, 100]\" or a pair (lo, hi)"))
                    })?;
                    if lo.is_nan() || hi.is_nan() || lo >= hi {
                        return Err(PyValueError::new_err(format!("{what}: range ({lo}, {hi}): lo must be below hi")));
                    }
                    // a pair is closed at its finite ends
                    let end = |e: f64| if e.is_infinite() { End::Unbounded } else { End::Closed(e) };
                    ParamRange { lo: end(lo), hi: end(hi) }
                }
            }
            "unit" => p.unit = leak(x.extract()?),
            "description" | "doc" => p.doc = leak(x.extract()?),
            other => {
                return Err(PyValueError::new_err(format!(
                    "{what}: unknown key `{other}`; known: default, range, unit, description"
                )))
            }
        }
    }
    if !has_default {
        return Err(PyValueError::new_err(format!("{what}: no \"default\"")));
    }
    Ok(p)
}

/// One `limits=` entry: a name, or (name, number or parameter name).
pub(crate) fn limit(v: &Bound<'_, PyAny>, params: &[Param]) -> PyResult<RuntimeLimit> {
    const KNOWN: &str = "\"high_reynolds\", \"dilute\", \"decreasing\", \"increasing\", \"packing_decreasing\", \
                         \"non_negative\", (\"stokes\", x), (\"einstein\", x), (\"static_friction\", x), (\"wall_length\", x)";
    let bad = || PyValueError::new_err(format!("limits: {v} is not a limit; known: {KNOWN}"));
    if let Ok(s) = v.extract::<String>() {
        return Ok(RuntimeLimit::Fixed(match s.as_str() {
            "high_reynolds" => Limit::HighReynolds,
            "dilute" => Limit::Dilute,
            "decreasing" => Limit::Decreasing,
            "increasing" => Limit::Increasing,
            "packing_decreasing" => Limit::PackingDecreasing,
            "non_negative" => Limit::NonNegative,
            "stokes" => Limit::Stokes { cd_re: 24.0 },
            "einstein" => Limit::Einstein { coefficient: 2.5 },
            _ => return Err(bad()),
        }));
    }
    let (kind, x): (String, Bound<'_, PyAny>) = v.extract().map_err(|_| bad())?;
    if let Ok(p) = x.extract::<String>() {
        let i = params
            .iter()
            .position(|q| q.name == p)
            .ok_or_else(|| PyValueError::new_err(format!("limits: ({kind:?}, {p:?}): no parameter `{p}` in params")))?;
        return match kind.as_str() {
            "stokes" => Ok(RuntimeLimit::StokesParam(i)),
            "einstein" => Ok(RuntimeLimit::EinsteinParam(i)),
            "static_friction" => Ok(RuntimeLimit::StaticFrictionParam(i)),
            "wall_length" => Ok(RuntimeLimit::WallLengthParam(i)),
            _ => Err(bad()),
        };
    }
    let x: f64 = x.extract().map_err(|_| bad())?;
    match kind.as_str() {
        "stokes" => Ok(RuntimeLimit::Fixed(Limit::Stokes { cd_re: x })),
        "einstein" => Ok(RuntimeLimit::Fixed(Limit::Einstein { coefficient: x })),
        "static_friction" => Ok(RuntimeLimit::Fixed(Limit::StaticFriction { mu_s: x })),
        "wall_length" => Ok(RuntimeLimit::Fixed(Limit::WallLength { kappa: x })),
        _ => Err(bad()),
    }
}

/// The parameters of `params=`, none of them an input or a keyword of `faces`.
pub(crate) fn declared_params(params: Option<&Bound<'_, PyDict>>, fam: Family, faces: &[Face]) -> PyResult<Vec<Param>> {
    let params: Vec<Param> = match params {
        Some(d) => d.iter().map(|(k, v)| param(&k.extract::<String>()?, &v)).collect::<PyResult<_>>()?,
        None => Vec::new(),
    };
    for face in faces {
        let (inputs, _, keywords) = runtime::face_io(*face);
        if let Some(p) = params.iter().find(|p| inputs.contains(&p.name.as_str())) {
            return Err(PyValueError::new_err(format!("params: `{}` is an input of the {fam} family", p.name)));
        }
        if let Some(p) = params.iter().find(|p| keywords.contains(&p.name.as_str())) {
            return Err(PyValueError::new_err(format!(
                "params: `{}` is a keyword the solver gives the {fam} function ({})",
                p.name,
                keywords.join(", ")
            )));
        }
    }
    Ok(params)
}

/// `limits=` as run-time limits.
pub(crate) fn declared_limits(limits: Option<&Bound<'_, PyAny>>, params: &[Param]) -> PyResult<Vec<RuntimeLimit>> {
    match limits.filter(|l| !l.is_none()) {
        Some(l) if l.is_instance_of::<PyList>() || l.is_instance_of::<PyTuple>() => {
            l.try_iter()?.map(|x| limit(&x?, params)).collect::<PyResult<_>>()
        }
        Some(l) => Err(PyTypeError::new_err(format!("limits: expected a list, found {l}"))),
        None => Ok(Vec::new()),
    }
}
