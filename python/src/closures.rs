//! Closures written in Python: `saltus.register_closure` puts a Python function in the
//! run-time registry of saltus-core ([`saltus_core::runtime`]), where the scene loader, the
//! model listing and `closure check` find it (what a registration declares is read by
//! [`crate::declarations`]).
//!
//! The function is called with the GIL taken inside the call (runs release it, and the DEM
//! calls drag from its rayon threads), once per batch the solver evaluates: a column, a
//! chunk of particles. Its inputs are fresh float64 arrays, its parameters floats.

use std::sync::Arc;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use saltus_core::closure::Family;
use saltus_core::param::{number, ParamRange};
use saltus_core::runtime::{self, BatchFunction, Control, Face, RuntimeLimit, RuntimeModel, Shape, Variate};
use saltus_core::{DragReynolds, Field, Needs, Param};

use crate::declarations::{declared_limits, declared_params, family_of, leak, limit, param};

/// A Python function as the law (one face) of a run-time closure.
struct PyFunction {
    function: Py<PyAny>,
    family: Family,
    /// the parameters' names, then the face's scalar keywords
    params: Vec<String>,
    inputs: Vec<&'static str>,
    outputs: &'static [&'static str],
    optional: &'static [&'static str],
}

impl BatchFunction for PyFunction {
    fn evaluate(&self, params: &[f64], inputs: &[&[f64]], outputs: &mut [&mut [f64]]) -> Result<usize, String> {
        Python::attach(|py| self.call(py, params, inputs, outputs))
    }
}

impl PyFunction {
    fn call(
        &self,
        py: Python<'_>,
        params: &[f64],
        inputs: &[&[f64]],
        outputs: &mut [&mut [f64]],
    ) -> Result<usize, String> {
        let raised = |e: PyErr| format!("the Python function raised {e}");
        let kwargs = PyDict::new(py);
        for (name, x) in self.inputs.iter().zip(inputs) {
            kwargs.set_item(name, PyArray1::from_slice(py, x)).map_err(raised)?;
        }
        for (name, &v) in self.params.iter().zip(params) {
            kwargs.set_item(name, v).map_err(raised)?;
        }
        let ret = self.function.bind(py).call((), Some(&kwargs)).map_err(raised)?;
        let n = inputs.first().map_or(0, |x| x.len());
        if let Ok(d) = ret.cast::<PyDict>() {
            let known = || {
                let optional = self.optional.iter().map(|o| format!(" (optional: {o})"));
                format!("{}{}", self.outputs.join(", "), optional.collect::<String>())
            };
            for k in d.keys() {
                let k = k.str().map(|s| s.to_string()).unwrap_or_default();
                if !self.outputs.contains(&k.as_str()) && !self.optional.contains(&k.as_str()) {
                    return Err(format!("the Python function returned `{k}`; the outputs are {}", known()));
                }
            }
            let mut written = 0;
            let names = self.outputs.iter().map(|n| (n, true)).chain(self.optional.iter().map(|n| (n, false)));
            for ((name, required), out) in names.zip(outputs.iter_mut()) {
                let Some(v) = d.get_item(name).map_err(raised)? else {
                    if required {
                        return Err(format!("the Python function returned no `{name}`; the outputs are {}", known()));
                    }
                    break;
                };
                self.copy(&v, name, inputs, out)?;
                written += 1;
            }
            return Ok(written);
        }
        match (self.outputs, outputs) {
            ([name], [out, ..]) => self.copy(&ret, name, inputs, out).map(|()| 1),
            _ => Err(format!(
                "the Python function returned {}; expected a dict of {} (float64 arrays of {n} values)",
                shown(&ret),
                self.outputs.join(", ")
            )),
        }
    }

    /// Output `name` from `v` into `out`: a 1-D float64 array of the inputs' length, every
    /// value finite (C_D may be +inf at Re_p = 0).
    fn copy(&self, v: &Bound<'_, PyAny>, name: &str, inputs: &[&[f64]], out: &mut [f64]) -> Result<(), String> {
        let n = out.len();
        let wrong = || format!("output `{name}` is {}; expected a float64 array of shape ({n},)", shown(v));
        let a: PyReadonlyArray1<'_, f64> = v.extract().map_err(|_| wrong())?;
        let a = a.as_array();
        if a.len() != n {
            return Err(wrong());
        }
        for (i, (o, &x)) in out.iter_mut().zip(a.iter()).enumerate() {
            if !runtime::accepts(self.family, name, x, inputs, i) {
                let at: Vec<String> =
                    self.inputs.iter().zip(inputs).map(|(k, c)| format!("{k} = {}", number(c[i]))).collect();
                return Err(format!("output `{name}` = {} at {}: not a finite number", number(x), at.join(", ")));
            }
            *o = x;
        }
        Ok(())
    }
}

/// What a returned object is, for a message: an array's dtype and shape, else its type.
fn shown(v: &Bound<'_, PyAny>) -> String {
    match (v.getattr("dtype"), v.getattr("shape")) {
        (Ok(d), Ok(s)) => format!("an array of dtype {d} and shape {s}"),
        _ => format!("a {}", v.get_type().name().map_or_else(|_| "?".to_string(), |n| n.to_string())),
    }
}

/// Face `face` of `fam` as the Python function `f`, with `extra` inputs after the face's own.
fn face_function(
    f: &Bound<'_, PyAny>,
    what: &str,
    fam: Family,
    face: Face,
    params: &[Param],
    extra: &[&'static str],
) -> PyResult<Arc<dyn BatchFunction>> {
    if !f.is_callable() {
        return Err(PyTypeError::new_err(format!("{what}: expected a function, found {f}")));
    }
    let (inputs, outputs, keywords) = runtime::face_io(face);
    let names = params.iter().map(|p| p.name.clone()).chain(keywords.iter().map(|k| k.to_string()));
    Ok(Arc::new(PyFunction {
        function: f.clone().unbind(),
        family: fam,
        params: names.collect(),
        inputs: inputs.iter().chain(extra).copied().collect(),
        outputs,
        optional: if matches!(face, Face::Plain(_)) { runtime::optional_outputs(fam) } else { &[] },
    }))
}

/// `saltus.register_rheology`, `register_kinetic_theory`, `register_mixing_length` and
/// `register_fluctuation` (`python/saltus/closures.py`): a closure of `kind` (`local`,
/// `kinetic`, `mixing_length`, `fluctuation`) whose faces are the Python functions of
/// `functions` (`evaluate`, and `inverse` or `diffusivity`), shaped by `options`.
#[pyfunction]
#[pyo3(signature = (kind, name, functions, params, source, equation, limits, options))]
#[allow(clippy::too_many_arguments)]
pub fn register_faces(
    kind: &str,
    name: &str,
    functions: &Bound<'_, PyDict>,
    params: Option<&Bound<'_, PyDict>>,
    source: String,
    equation: String,
    limits: Option<&Bound<'_, PyAny>>,
    options: &Bound<'_, PyDict>,
) -> PyResult<()> {
    let function = |k: &str| functions.get_item(k).ok().flatten().filter(|v| !v.is_none());
    let option = |k: &str| options.get_item(k).ok().flatten().filter(|v| !v.is_none());
    let evaluate = function("evaluate").ok_or_else(|| PyTypeError::new_err("evaluate: expected a function"))?;
    let (fam, faces): (Family, Vec<Face>) = match kind {
        "local" | "kinetic" => (Family::Granular, Vec::new()),
        "mixing_length" => (Family::Turbulence, vec![Face::MixingLength]),
        "fluctuation" => (Family::Fluctuation, vec![Face::Draw, Face::Diffusivity]),
        other => return Err(PyValueError::new_err(format!("unknown kind `{other}`"))),
    };
    let mut params_v = declared_params(params, fam, &faces)?;
    let (function, shape) = match kind {
        "local" => {
            let control_name: String = option("control").map_or(Ok("i".to_string()), |c| c.extract())?;
            let control = Control::from_name(&control_name).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "control: `{control_name}`; allowed: \"i\" (inertial number), \"j\" (viscous number), \"k\" (J + alpha I^2)"
                ))
            })?;
            let faces = [Face::Rheology(control), Face::Inverse(control)];
            params_v = declared_params(params, fam, &faces)?;
            let f = face_function(&evaluate, "friction_packing", fam, faces[0], &params_v, &[])?;
            let inverse =
                function("inverse").map(|g| face_function(&g, "inverse", fam, faces[1], &params_v, &[])).transpose()?;
            (f, Shape::Local { control, inverse })
        }
        "kinetic" => {
            params_v = declared_params(params, fam, &[Face::Kinetic])?;
            // the elastic law's parameters, with the proposed model's defaults when not declared
            let defaults = [
                (
                    "p0",
                    0.05,
                    ParamRange::positive(),
                    "Pa",
                    "elastic modulus P0 of the Johnson-Jackson pressure (eq 2.14)",
                ),
                (
                    "phi_rlp",
                    0.57,
                    ParamRange::open(0.0, 1.0),
                    "-",
                    "random loose packing where the elastic pressure starts",
                ),
                (
                    "phi_max",
                    0.635,
                    ParamRange::open(0.0, 1.0),
                    "-",
                    "maximum packing where the elastic pressure diverges",
                ),
                (
                    "static_friction",
                    0.146 + 0.228 * (0.4f64 / 0.232).tanh(),
                    ParamRange::closed(0.0, 2.0),
                    "-",
                    "Coulomb friction mu_s of the elastic shear stress (eq 2.15; default eq B1 at mu_p = 0.4)",
                ),
            ];
            for (n, v, range, unit, doc) in defaults {
                if !params_v.iter().any(|p| p.name == n) {
                    params_v.push(Param::new(n, v, range, unit, doc));
                }
            }
            let saltation = option("saltation").map_or(Ok(false), |v| v.extract::<bool>())?;
            let dissipation: String =
                option("drag_dissipation").map_or(Ok("quadratic".to_string()), |v| v.extract())?;
            let linear = match dissipation.as_str() {
                "linear" => true,
                "quadratic" => false,
                other => {
                    return Err(PyValueError::new_err(format!(
                        "drag_dissipation: `{other}`; allowed: \"linear\" (c_J = 3, eq 2.25), \"quadratic\" (3 + 2 C_D^inf / C_D, eq 3.13)"
                    )))
                }
            };
            let f = face_function(&evaluate, "coefficients", fam, Face::Kinetic, &params_v, &[])?;
            (f, Shape::Kinetic { saltation, linear_drag_dissipation: linear })
        }
        "mixing_length" => {
            (face_function(&evaluate, "mixing_length", fam, Face::MixingLength, &params_v, &[])?, Shape::MixingLength)
        }
        _ => {
            let mut variates = Vec::new();
            let mut names: Vec<&'static str> = Vec::new();
            if let Some(v) = option("variates") {
                let d = v.cast::<PyDict>().map_err(|_| {
                    PyTypeError::new_err("variates: a dict of input name -> \"normal\", \"exponential\" or \"uniform\"")
                })?;
                for (k, kind) in d.iter() {
                    let (k, kind): (String, String) = (k.extract()?, kind.extract()?);
                    let v = Variate::from_name(&kind).ok_or_else(|| {
                        PyValueError::new_err(format!(
                            "variates[{k:?}]: `{kind}`; allowed: \"normal\", \"exponential\", \"uniform\""
                        ))
                    })?;
                    let (inputs, _, keywords) = runtime::face_io(Face::Draw);
                    if inputs.contains(&k.as_str())
                        || keywords.contains(&k.as_str())
                        || params_v.iter().any(|p| p.name == k)
                    {
                        return Err(PyValueError::new_err(format!(
                            "variates: `{k}` is already an input, keyword or parameter"
                        )));
                    }
                    variates.push(v);
                    names.push(leak(k));
                }
            }
            let mut needs = Vec::new();
            if let Some(n) = option("needs") {
                for f in n.try_iter()? {
                    let f: String = f?.extract()?;
                    needs.push(match f.as_str() {
                        "k" => Field::Tke,
                        "omega" => Field::Omega,
                        "nu_t" => Field::EddyViscosity,
                        "reynolds_stress" => Field::ReynoldsStress,
                        other => {
                            return Err(PyValueError::new_err(format!(
                                "needs: `{other}`; allowed: \"k\", \"omega\", \"nu_t\", \"reynolds_stress\""
                            )))
                        }
                    });
                }
            }
            let draw = face_function(&evaluate, "draw", fam, Face::Draw, &params_v, &names)?;
            let diffusivity = function("diffusivity")
                .ok_or_else(|| PyTypeError::new_err("diffusivity: expected a function (the mean-field face)"))?;
            let diffusivity = face_function(&diffusivity, "diffusivity", fam, Face::Diffusivity, &params_v, &[])?;
            (draw, Shape::Fluctuation { diffusivity, variates, needs: Needs::of(&needs) })
        }
    };
    let limits = declared_limits(limits, &params_v)?;
    runtime::register(RuntimeModel {
        family: fam,
        name: leak(name.to_string()),
        source: leak(source),
        equation: leak(equation),
        params: params_v,
        limits,
        convention: DragReynolds::Interstitial,
        depends_on_reynolds: true,
        function,
        shape,
        build: saltus_closures::runtime::build,
    })
    .map_err(|e| PyValueError::new_err(format!("register ({fam}, {name:?}): {e}")))
}

/// `saltus.register_closure`: see `python/saltus/__init__.py`.
#[pyfunction]
#[pyo3(signature = (family, name, evaluate, params, source, equation, limits, reynolds, depends_on_reynolds))]
#[allow(clippy::too_many_arguments)]
pub fn register_closure(
    family: &str,
    name: &str,
    evaluate: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
    source: String,
    equation: String,
    limits: Option<&Bound<'_, PyAny>>,
    reynolds: &str,
    depends_on_reynolds: bool,
) -> PyResult<()> {
    let fam = family_of(family)?;
    let (inputs, outputs) = runtime::io(fam).ok_or_else(|| {
        PyValueError::new_err(format!(
            "family `{fam}` takes its closures through saltus.register_rheology, register_kinetic_theory, \
             register_mixing_length or register_fluctuation; register_closure takes the others, allowed: drag, hindrance, \
             viscosity, wall_friction"
        ))
    })?;
    if !evaluate.is_callable() {
        return Err(PyTypeError::new_err(format!("evaluate: expected a function, found {evaluate}")));
    }
    let params: Vec<Param> = match params {
        Some(d) => d.iter().map(|(k, v)| param(&k.extract::<String>()?, &v)).collect::<PyResult<_>>()?,
        None => Vec::new(),
    };
    let clash = params.iter().find(|p| inputs.contains(&p.name.as_str()));
    if let Some(p) = clash {
        return Err(PyValueError::new_err(format!("params: `{}` is an input of the {fam} family", p.name)));
    }
    let limits: Vec<RuntimeLimit> = match limits.filter(|l| !l.is_none()) {
        Some(l) if l.is_instance_of::<PyList>() || l.is_instance_of::<PyTuple>() => {
            l.try_iter()?.map(|x| limit(&x?, &params)).collect::<PyResult<_>>()?
        }
        Some(l) => return Err(PyTypeError::new_err(format!("limits: expected a list, found {l}"))),
        None => Vec::new(),
    };
    let convention = match reynolds {
        "interstitial" => DragReynolds::Interstitial,
        "superficial" => DragReynolds::Superficial,
        other => {
            return Err(PyValueError::new_err(format!(
                "reynolds: `{other}`; allowed: \"interstitial\" (Re_p), \"superficial\" ((1 - phi) Re_p)"
            )))
        }
    };
    let function = PyFunction {
        function: evaluate.clone().unbind(),
        family: fam,
        params: params.iter().map(|p| p.name.clone()).collect(),
        inputs: inputs.to_vec(),
        outputs,
        optional: runtime::optional_outputs(fam),
    };
    runtime::register(RuntimeModel {
        family: fam,
        name: leak(name.to_string()),
        source: leak(source),
        equation: leak(equation),
        params,
        limits,
        convention,
        depends_on_reynolds,
        function: Arc::new(function),
        shape: Shape::Plain,
        build: saltus_closures::runtime::build,
    })
    .map_err(|e| PyValueError::new_err(format!("register_closure({family:?}, {name:?}): {e}")))
}

/// `saltus.unregister_closure`: whether `name` of `family` was registered at run time.
#[pyfunction]
pub fn unregister_closure(family: &str, name: &str) -> PyResult<bool> {
    Ok(runtime::unregister(family_of(family)?, name))
}
