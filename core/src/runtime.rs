//! Closures registered while the program runs, beside the compile-time registry of
//! [`crate::registry`]: a model whose law is a function over arrays (a closure written in
//! Python, `saltus.register_closure`), named in a scene like any other model.
//!
//! typetag knows only the names compiled in, so the scene loader
//! ([`crate::scene::closure_from_value`]) looks a name up here when typetag does not know
//! it, reads the parameters with the ranges the registration declared, and builds the model
//! with the registration's [`RuntimeModel::build`] (the adapters of
//! `saltus_closures::runtime`, which implement the family traits by calling the function on
//! whole slices). Every family can hold one; each face of a family is a function of
//! named arrays ([`face_io`]): the granular local rheology (friction and packing of the
//! control number, optionally the packing inverse), the kinetic-theory coefficient set,
//! the algebraic mixing length, and the mean-field and particle faces of a fluctuation
//! model. Two-equation turbulence is not one of them ([`Shape`]).

use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, PoisonError, RwLock};

use crate::closure::Family;
use crate::needs::Needs;
use crate::param::{Describe, Limit, Param, ParamError};
use crate::{
    DragLaw, DragReynolds, EffectiveViscosity, Fluctuation, GranularStress, Hindrance, Turbulence, WallFriction,
};

/// Families a run-time closure may belong to: every one.
pub const FAMILIES: [Family; 7] = Family::ALL;

/// Input names and output names of the function of a run-time closure of `family` whose
/// model has one face (drag, hindrance, viscosity, wall friction): the names `saltus
/// closure eval` uses. `None` for the families whose faces depend on the model's
/// [`Shape`] ([`face_io`]).
pub fn io(family: Family) -> Option<(&'static [&'static str], &'static [&'static str])> {
    match family {
        Family::Drag => Some((&["re_p"], &["cd"])),
        Family::Hindrance => Some((&["phi", "re_p"], &["factor"])),
        Family::Viscosity => Some((&["phi"], &["nu_ratio"])),
        Family::WallFriction => Some((&["re"], &["f_re"])),
        Family::Granular | Family::Turbulence | Family::Fluctuation => None,
    }
}

/// The control number of a run-time local rheology, computed by the solver from the local
/// state (the definitions of [`crate::LocalState`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// inertial number I = d |gamma_dot| / sqrt(p / rho_p), input `i`
    Inertial,
    /// viscous number J = eta_f |gamma_dot| / p, input `j`
    Viscous,
    /// K = J + alpha I^2 (Fry 2024 eq 36), input `k`; `alpha` is a parameter of the model
    Combined,
}

impl Control {
    /// Input name of the control number.
    pub fn name(self) -> &'static str {
        match self {
            Control::Inertial => "i",
            Control::Viscous => "j",
            Control::Combined => "k",
        }
    }

    /// The control number from its name.
    pub fn from_name(name: &str) -> Option<Control> {
        [Control::Inertial, Control::Viscous, Control::Combined].into_iter().find(|c| c.name() == name)
    }
}

/// A random variate of a run-time particle draw, taken from the particle's seeded stream
/// in the order declared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variate {
    /// standard normal (mean 0, variance 1)
    Normal,
    /// exponential of rate 1
    Exponential,
    /// uniform on [0, 1)
    Uniform,
}

impl Variate {
    /// Name in a registration.
    pub fn name(self) -> &'static str {
        match self {
            Variate::Normal => "normal",
            Variate::Exponential => "exponential",
            Variate::Uniform => "uniform",
        }
    }

    /// The variate from its name.
    pub fn from_name(name: &str) -> Option<Variate> {
        [Variate::Normal, Variate::Exponential, Variate::Uniform].into_iter().find(|v| v.name() == name)
    }
}

/// What a run-time closure implements beside [`RuntimeModel::function`]. Two-equation
/// turbulence has no run-time shape: its closure is several coupled source terms, wall
/// values and initial states of transported fields the solver advances, not one function
/// of the column's arrays.
#[derive(Clone, Default)]
pub enum Shape {
    /// drag, hindrance, viscosity, wall friction: one function of [`io`]
    #[default]
    Plain,
    /// a granular local rheology: `function` is friction and packing of the control
    /// number ([`Face::Rheology`]); `inverse` the control number of a packing
    /// ([`Face::Inverse`]), else the solver bisects on arrays
    Local {
        /// the control number
        control: Control,
        /// the packing inverse, when given
        inverse: Option<Arc<dyn BatchFunction>>,
    },
    /// a kinetic-theory coefficient set ([`Face::Kinetic`]); the elastic pressure, its
    /// Coulomb friction and the drag dissipation are the built-in Johnson-Jackson ones of
    /// the parameters `p0`, `phi_rlp`, `phi_max` and `static_friction`
    Kinetic {
        /// whether the solver passes the saltation input (sqrt_t, k_drag) of Chassagne et
        /// al. 2023 eq 3.6; without, both are 0
        saltation: bool,
        /// the drag dissipation factor c_J: 3 (eq 2.25) if true, else 3 + 2 C_D^inf / C_D
        /// (eq 3.13)
        linear_drag_dissipation: bool,
    },
    /// an algebraic turbulence closure: `function` is the mixing length ([`Face::MixingLength`])
    MixingLength,
    /// a fluctuation model: `function` is the particle draw ([`Face::Draw`])
    Fluctuation {
        /// the mean-field face ([`Face::Diffusivity`])
        diffusivity: Arc<dyn BatchFunction>,
        /// the variates of one draw, in order
        variates: Vec<Variate>,
        /// the fields the model reads from the turbulence closure
        needs: Needs,
    },
}

/// One function of a run-time closure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// the one function of a drag, hindrance, viscosity or wall-friction law
    Plain(Family),
    /// friction `mu` and packing `phi` of the control number
    Rheology(Control),
    /// the control number of a packing `phi`
    Inverse(Control),
    /// the kinetic-theory coefficients of `phi` (and the saltation input)
    Kinetic,
    /// the mixing length `l_m` over the cells of one column
    MixingLength,
    /// the particle diffusivity over the cells of one column
    Diffusivity,
    /// one draw per particle
    Draw,
}

/// Input names, output names and the scalar keywords (after the parameters) of a face:
/// the grain properties of a granular closure, the grain diameter and fluid viscosity of
/// a mixing length, the flow scales of a fluctuation model. The draw's variates follow
/// its inputs under the names given at registration.
pub fn face_io(face: Face) -> (&'static [&'static str], &'static [&'static str], &'static [&'static str]) {
    const GRAIN: &[&str] = &["diameter", "density", "restitution", "friction"];
    const SCALES: &[&str] = &["depth", "bulk_velocity"];
    match face {
        Face::Plain(f) => io(f).map_or((&[], &[], &[]), |(i, o)| (i, o, &[])),
        Face::Rheology(c) => (std::slice::from_ref(CONTROL_NAMES[c as usize]), &["mu", "phi"], GRAIN),
        Face::Inverse(c) => (&["phi"], std::slice::from_ref(CONTROL_NAMES[c as usize]), GRAIN),
        Face::Kinetic => (&["phi", "sqrt_t", "k_drag"], &["g0", "f1", "f2", "f3", "f4", "e_eff"], GRAIN),
        Face::MixingLength => (&["z", "dz", "phi", "dudz"], &["l_m"], &["diameter", "nu_f"]),
        Face::Diffusivity => (&["k", "omega", "nu_t", "reynolds_stress"], &["diffusivity"], SCALES),
        Face::Draw => (
            &["k", "omega", "nu_t", "reynolds_stress", "slip", "response_time"],
            &["u_x", "u_y", "u_z", "duration"],
            SCALES,
        ),
    }
}

const CONTROL_NAMES: [&&str; 3] = [&"i", &"j", &"k"];

/// Most variates one run-time particle draw may declare.
pub const MAX_VARIATES: usize = 16;

/// Parameters every run-time kinetic-theory closure has (declared by the registration when
/// it does not declare them itself): the Johnson-Jackson elastic law of Chassagne et al.
/// 2023 eq 2.14 and its Coulomb friction (eq 2.15), with the defaults of the paper's
/// proposed model (mu_s of eq B1 at mu_p = 0.4).
pub const KINETIC_PARAMS: [&str; 4] = ["p0", "phi_rlp", "phi_max", "static_friction"];

/// Outputs of the kinetic-theory face ([`Face::Kinetic`]) that may be +inf ([`accepts`]).
const KINETIC_DIVERGENT: [&str; 5] = ["g0", "f1", "f2", "f3", "f4"];

/// Outputs a function of `family` may return beside those of [`io`]: C_D Re_p (`cd_re`)
/// of a drag law, which the solvers use where given (finite at Re_p = 0, and written as
/// the law's own algebra: Dallavalle's c Re_p + a rather than (c + a / Re_p) Re_p).
pub fn optional_outputs(family: Family) -> &'static [&'static str] {
    match family {
        Family::Drag => &["cd_re"],
        _ => &[],
    }
}

/// Whether output `output` = `value` of a run-time closure of `family` at row `row` of
/// `inputs` is usable: finite, or C_D = +inf at Re_p = 0 (a drag law with a Stokes limit,
/// whose `cd_re` the solvers then use), or a draw's `duration` = +inf (no fluctuation
/// until the flow has a turnover time), or a packing inverse's control number = +inf
/// (phi <= 0), or a kinetic-theory coefficient g0, F1-F4 = +inf at phi > 0: they diverge
/// at the packing where g0 does (Chassagne et al. 2023 eqs 2.23 and 3.2, g0 ~
/// (phi_max - phi)^{-3/2}), which the built-in `frictional_collisional` returns as +inf
/// from phi_max on. Its `e_eff`, a restitution, must be finite.
pub fn accepts(family: Family, output: &str, value: f64, inputs: &[&[f64]], row: usize) -> bool {
    value.is_finite()
        || (family == Family::Fluctuation && output == "duration" && value == f64::INFINITY)
        || (family == Family::Granular && Control::from_name(output).is_some() && value == f64::INFINITY)
        || (family == Family::Granular
            && KINETIC_DIVERGENT.contains(&output)
            && value == f64::INFINITY
            && inputs.first().and_then(|phi| phi.get(row)).is_some_and(|&phi| phi > 0.0))
        || (family == Family::Drag
            && output == "cd"
            && value == f64::INFINITY
            && inputs.first().and_then(|re| re.get(row)) == Some(&0.0))
}

/// Why a run-time closure of `family` cannot have `shape`, naming what it can have.
pub fn refused(family: Family) -> String {
    let allowed = match family {
        Family::Drag | Family::Hindrance | Family::Viscosity | Family::WallFriction => "one function",
        Family::Granular => {
            "a local rheology (friction and packing of a control number) or a kinetic-theory coefficient set"
        }
        Family::Turbulence => {
            "a mixing length (two-equation closures are compiled models: their source terms, wall values and \
             initial states are not one function of the column)"
        }
        Family::Fluctuation => "a particle draw with its mean-field diffusivity",
    };
    format!("a run-time closure of family `{family}` is {allowed}")
}

/// Whether `shape` is one a run-time closure of `family` may have.
fn fits(family: Family, shape: &Shape) -> bool {
    matches!(
        (family, shape),
        (Family::Drag | Family::Hindrance | Family::Viscosity | Family::WallFriction, Shape::Plain)
            | (Family::Granular, Shape::Local { .. } | Shape::Kinetic { .. })
            | (Family::Turbulence, Shape::MixingLength)
            | (Family::Fluctuation, Shape::Fluctuation { .. })
    )
}

/// The law of a run-time closure: named arrays in, named arrays out.
pub trait BatchFunction: Send + Sync {
    /// Evaluate with `params` (the values of [`RuntimeModel::params`], in order, then the
    /// scalar keywords of the face, [`face_io`]) on `inputs` (one slice per input name of
    /// the face, all of one length), writing `outputs`: one slice per output name of the
    /// face, then possibly slices for the first [`optional_outputs`], each of the inputs'
    /// length. Returns how many of `outputs` it
    /// wrote: every required one, then the optional ones it gives, in order. `Err` is a
    /// message for the user (the function raised, or returned something else than the
    /// outputs); the outputs are then undefined.
    fn evaluate(&self, params: &[f64], inputs: &[&[f64]], outputs: &mut [&mut [f64]]) -> Result<usize, String>;
}

/// A limit a run-time closure declares: a [`Limit`], or one whose number is the value of
/// a parameter (Dallavalle's C_D Re_p -> a).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RuntimeLimit {
    /// as given
    Fixed(Limit),
    /// [`Limit::Stokes`] with `cd_re` the parameter of this index
    StokesParam(usize),
    /// [`Limit::Einstein`] with `coefficient` the parameter of this index
    EinsteinParam(usize),
    /// [`Limit::StaticFriction`] with `mu_s` the parameter of this index
    StaticFrictionParam(usize),
    /// [`Limit::WallLength`] with `kappa` the parameter of this index
    WallLengthParam(usize),
}

impl RuntimeLimit {
    /// The limit at parameter values `values`.
    pub fn at(self, values: &[f64]) -> Limit {
        let value = |i: usize| values.get(i).copied().unwrap_or(f64::NAN);
        match self {
            RuntimeLimit::Fixed(l) => l,
            RuntimeLimit::StokesParam(i) => Limit::Stokes { cd_re: value(i) },
            RuntimeLimit::EinsteinParam(i) => Limit::Einstein { coefficient: value(i) },
            RuntimeLimit::StaticFrictionParam(i) => Limit::StaticFriction { mu_s: value(i) },
            RuntimeLimit::WallLengthParam(i) => Limit::WallLength { kappa: value(i) },
        }
    }
}

/// A closure of any family as built: the family trait object. A scene's closure table
/// ([`Built::from_value`]) and a run-time model (`RuntimeModel`'s `build`) both give one;
/// `closure eval` and `closure check` work on it.
#[derive(Debug)]
pub enum Built {
    /// a drag law
    Drag(Box<dyn DragLaw>),
    /// a hindrance
    Hindrance(Box<dyn Hindrance>),
    /// an effective viscosity
    Viscosity(Box<dyn EffectiveViscosity>),
    /// a side-wall friction law
    WallFriction(Box<dyn WallFriction>),
    /// a granular stress
    Granular(Box<dyn GranularStress>),
    /// an algebraic turbulence closure
    Turbulence(Box<dyn Turbulence>),
    /// a fluctuation model
    Fluctuation(Box<dyn Fluctuation>),
}

impl Built {
    /// The model's name, equation, source and parameters with their values.
    pub fn describe(&self) -> &dyn Describe {
        match self {
            Built::Drag(m) => m.as_ref(),
            Built::Hindrance(m) => m.as_ref(),
            Built::Viscosity(m) => m.as_ref(),
            Built::WallFriction(m) => m.as_ref(),
            Built::Granular(m) => m.as_ref(),
            Built::Turbulence(m) => m.as_ref(),
            Built::Fluctuation(m) => m.as_ref(),
        }
    }
}

/// A family trait object that a [`Built`] may hold.
pub trait FromRuntime {
    /// The model of this family, `None` when `built` is of another family.
    fn from_runtime(built: Built) -> Option<Box<Self>>;
}

macro_rules! from_runtime {
    ($($trait_:ident => $variant:ident),* ; $($none:ident),*) => {
        $(impl FromRuntime for dyn $trait_ {
            fn from_runtime(built: Built) -> Option<Box<Self>> {
                match built {
                    Built::$variant(m) => Some(m),
                    _ => None,
                }
            }
        })*
        $(impl FromRuntime for dyn $none {
            fn from_runtime(_: Built) -> Option<Box<Self>> {
                None
            }
        })*
    };
}

from_runtime!(DragLaw => Drag, Hindrance => Hindrance, EffectiveViscosity => Viscosity, WallFriction => WallFriction,
    GranularStress => Granular, Turbulence => Turbulence, Fluctuation => Fluctuation;);

/// One run-time closure: what the registry lists and the scene loader checks, and how to
/// build it. Strings are `'static` because [`crate::Describe`] hands them out so; a
/// registration leaks its few strings once. It describes its default instance.
#[derive(Clone)]
pub struct RuntimeModel {
    /// family, one of [`FAMILIES`]
    pub family: Family,
    /// the `type` a scene names it by
    pub name: &'static str,
    /// where the law comes from
    pub source: &'static str,
    /// the law, one line
    pub equation: &'static str,
    /// parameters with their defaults as `value`, ranges, units and descriptions
    pub params: Vec<Param>,
    /// limits checked by `saltus closure check`
    pub limits: Vec<RuntimeLimit>,
    /// hindrance only: the Reynolds number at which C_D is evaluated
    pub convention: DragReynolds,
    /// hindrance only: whether the factor depends on Re_p
    pub depends_on_reynolds: bool,
    /// the law (of a model with several faces, the one [`Shape`] names)
    pub function: Arc<dyn BatchFunction>,
    /// the faces of the family: which functions the model has and how the solver calls them
    pub shape: Shape,
    /// the family trait object at the given parameter values (in the order of `params`,
    /// each within its range)
    pub build: fn(&Arc<RuntimeModel>, Vec<f64>) -> Result<Built, String>,
}

impl fmt::Debug for RuntimeModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RuntimeModel").field("family", &self.family).field("name", &self.name).finish_non_exhaustive()
    }
}

impl RuntimeModel {
    /// Parameters at `values` (in order).
    pub fn params_at(&self, values: &[f64]) -> Vec<Param> {
        self.params.iter().zip(values).map(|(p, &v)| Param { value: v, ..p.clone() }).collect()
    }

    /// The first parameter value outside its range.
    pub fn check_values(&self, values: &[f64]) -> Result<(), ParamError> {
        for (p, &v) in self.params.iter().zip(values) {
            if !p.range.contains(v) {
                return Err(ParamError::new(p.name.clone(), v, p.range.to_string()));
            }
        }
        Ok(())
    }
}

impl Describe for RuntimeModel {
    fn name(&self) -> &'static str {
        self.name
    }
    fn source(&self) -> &'static str {
        self.source
    }
    fn equation(&self) -> &'static str {
        self.equation
    }
    fn params(&self) -> Vec<Param> {
        self.params.clone()
    }
    fn limits(&self) -> Vec<Limit> {
        let defaults: Vec<f64> = self.params.iter().map(|p| p.value).collect();
        self.limits.iter().map(|l| l.at(&defaults)).collect()
    }
}

static MODELS: RwLock<Vec<Arc<RuntimeModel>>> = RwLock::new(Vec::new());

fn read() -> std::sync::RwLockReadGuard<'static, Vec<Arc<RuntimeModel>>> {
    // the list is replaced whole under the lock: a panic elsewhere cannot leave it half-made
    MODELS.read().unwrap_or_else(PoisonError::into_inner)
}

/// Register `model`, replacing a run-time closure of the same family and name (a notebook
/// cell run again); models already built keep the law they were built with. Refused: a
/// name that is not a plain identifier or that a compiled
/// model of the family carries, parameter names repeated or `type`, a default outside its
/// range, a shape the family cannot have ([`Shape`]).
pub fn register(model: RuntimeModel) -> Result<(), String> {
    let (family, name) = (model.family, model.name);
    if !fits(family, &model.shape) {
        return Err(refused(family));
    }
    if matches!(&model.shape, Shape::Fluctuation { variates, .. } if variates.len() > MAX_VARIATES) {
        return Err(format!("a draw takes at most {MAX_VARIATES} variates"));
    }
    let has = |name: &str| model.params.iter().any(|p| p.name == name);
    if matches!(model.shape, Shape::Local { control: Control::Combined, .. }) && !has("alpha") {
        return Err("a rheology of K = J + alpha I^2 needs a parameter `alpha`".into());
    }
    if let Some(missing) = KINETIC_PARAMS.iter().find(|p| matches!(model.shape, Shape::Kinetic { .. }) && !has(p)) {
        return Err(format!("a kinetic-theory coefficient set needs a parameter `{missing}`"));
    }
    let plain = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !plain {
        return Err(format!("name `{name}`: use letters, digits and _ (a TOML `type` value), starting with a letter"));
    }
    if crate::registry::models_of(family).iter().any(|m| m.name == name) {
        return Err(format!("name `{name}`: a built-in {family} model has it; choose another"));
    }
    for (i, p) in model.params.iter().enumerate() {
        if p.name == "type" || p.name.is_empty() || p.name.contains('.') {
            return Err(format!("parameter `{}`: not a usable key (empty, dotted or `type`)", p.name));
        }
        if model.params[..i].iter().any(|q| q.name == p.name) {
            return Err(format!("parameter `{}` given twice", p.name));
        }
        if !p.range.contains(p.value) {
            return Err(format!("parameter `{}`: default {} outside its range {}", p.name, p.value, p.range));
        }
    }
    for l in &model.limits {
        if let RuntimeLimit::StokesParam(i)
        | RuntimeLimit::EinsteinParam(i)
        | RuntimeLimit::StaticFrictionParam(i)
        | RuntimeLimit::WallLengthParam(i) = l
        {
            if *i >= model.params.len() {
                return Err(format!("a limit names parameter {i}, which does not exist"));
            }
        }
    }
    let mut all = MODELS.write().unwrap_or_else(PoisonError::into_inner);
    all.retain(|m| !(m.family == family && m.name == name));
    all.push(Arc::new(model));
    Ok(())
}

/// Remove the run-time closure `name` of `family`; whether there was one.
pub fn unregister(family: Family, name: &str) -> bool {
    let mut all = MODELS.write().unwrap_or_else(PoisonError::into_inner);
    let before = all.len();
    all.retain(|m| !(m.family == family && m.name == name));
    all.len() != before
}

/// The run-time closure `name` of `family`.
pub fn lookup(family: Family, name: &str) -> Option<Arc<RuntimeModel>> {
    read().iter().find(|m| m.family == family && m.name == name).cloned()
}

/// Run-time closures of `family` (every family when `None`), sorted by family then name.
pub fn models(family: Option<Family>) -> Vec<Arc<RuntimeModel>> {
    let mut v: Vec<_> = read().iter().filter(|m| family.is_none_or(|f| f == m.family)).cloned().collect();
    v.sort_by(|a, b| (a.family, a.name).cmp(&(b.family, b.name)));
    v
}

/// Comma-separated names of a family's models (for error messages): the compiled ones
/// ([`crate::registry`]), then those registered at run time.
pub fn known_names(family: Family) -> String {
    let runtime = models(Some(family));
    crate::registry::models_of(family)
        .iter()
        .map(|m| m.name)
        .chain(runtime.iter().map(|m| m.name))
        .collect::<Vec<_>>()
        .join(", ")
}

static PYTHON_HOST: AtomicBool = AtomicBool::new(false);

/// Declare that this process runs a Python interpreter that imports a scene's `[python]
/// modules` before loading it (the Python package does, when it is imported); without it
/// a scene with `[python]` is refused ([`crate::scene::Python::refused`]).
pub fn set_python_host() {
    PYTHON_HOST.store(true, Ordering::Relaxed);
}

/// Whether [`set_python_host`] was called.
pub fn python_host() -> bool {
    PYTHON_HOST.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinetic_coefficients_may_diverge_where_the_packing_is_positive() {
        let (phi, zero) = ([0.3, 0.64], [0.0]);
        for name in KINETIC_DIVERGENT {
            assert!(accepts(Family::Granular, name, f64::INFINITY, &[&phi], 1), "{name}");
            assert!(accepts(Family::Granular, name, 2.5, &[&phi], 0), "{name}");
            // g0 = 1 in the dilute limit: +inf there is a wrong law
            assert!(!accepts(Family::Granular, name, f64::INFINITY, &[&zero], 0), "{name}");
            assert!(!accepts(Family::Granular, name, f64::NEG_INFINITY, &[&phi], 1), "{name}");
            assert!(!accepts(Family::Granular, name, f64::NAN, &[&phi], 1), "{name}");
            // a coefficient of another family is not one
            assert!(!accepts(Family::Viscosity, name, f64::INFINITY, &[&phi], 1), "{name}");
        }
        assert!(!accepts(Family::Granular, "e_eff", f64::INFINITY, &[&phi], 1));
        assert!(!accepts(Family::Granular, "mu", f64::INFINITY, &[&phi], 1));
    }

    #[test]
    fn other_infinities_stay_as_they_were() {
        assert!(accepts(Family::Fluctuation, "duration", f64::INFINITY, &[&[0.0]], 0));
        assert!(!accepts(Family::Fluctuation, "u_x", f64::INFINITY, &[&[0.0]], 0));
        assert!(accepts(Family::Granular, "i", f64::INFINITY, &[&[0.0]], 0));
        assert!(accepts(Family::Drag, "cd", f64::INFINITY, &[&[0.0]], 0));
        assert!(!accepts(Family::Drag, "cd", f64::INFINITY, &[&[1.0]], 0));
    }
}
