//! Closures registered while the program runs, beside the compile-time registry of
//! [`crate::registry`]: a model whose law is a function over arrays (a closure written in
//! Python, `saltus.register_closure`), named in a scene like any other model.
//!
//! typetag knows only the names compiled in, so the scene loader
//! ([`crate::scene::closure_from_value`]) looks a name up here when typetag does not know
//! it, reads the parameters with the ranges the registration declared, and builds the model
//! with the registration's [`RuntimeModel::build`] (the adapters of
//! `saltus_closures::runtime`, which implement the family traits by calling the function on
//! whole slices). Only families whose trait is a function of arrays of numbers are
//! accepted: [`FAMILIES`].

use std::fmt;
use std::sync::{Arc, PoisonError, RwLock};

use crate::closure::Family;
use crate::param::{Describe, Limit, Param, ParamError};
use crate::{
    DragLaw, DragReynolds, EffectiveViscosity, Fluctuation, GranularStress, Hindrance, Turbulence, WallFriction,
};

/// Families a run-time closure may belong to: those whose trait is a function of arrays of
/// numbers. The granular stress (two faces, a packing inverse and a pressure solved by
/// bisection, grain properties inherited), turbulence (column views, transported fields)
/// and fluctuation (a seeded random draw per particle) are not.
pub const FAMILIES: [Family; 4] = [Family::Drag, Family::Hindrance, Family::Viscosity, Family::WallFriction];

/// Input names and output names of the function of a run-time closure of `family`: the
/// names `saltus closure eval` uses. `None` for a family outside [`FAMILIES`].
pub fn io(family: Family) -> Option<(&'static [&'static str], &'static [&'static str])> {
    match family {
        Family::Drag => Some((&["re_p"], &["cd"])),
        Family::Hindrance => Some((&["phi", "re_p"], &["factor"])),
        Family::Viscosity => Some((&["phi"], &["nu_ratio"])),
        Family::WallFriction => Some((&["re"], &["f_re"])),
        Family::Granular | Family::Turbulence | Family::Fluctuation => None,
    }
}

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
/// whose `cd_re` the solvers then use).
pub fn accepts(family: Family, output: &str, value: f64, inputs: &[&[f64]], row: usize) -> bool {
    value.is_finite()
        || (family == Family::Drag
            && output == "cd"
            && value == f64::INFINITY
            && inputs.first().and_then(|re| re.get(row)) == Some(&0.0))
}

/// Why `family` cannot hold a run-time closure, naming those that can.
pub fn refused(family: Family) -> String {
    let allowed: Vec<&str> = FAMILIES.iter().map(|f| f.key()).collect();
    format!(
        "family `{family}` cannot take a closure registered at run time (its trait is not a function of \
         arrays); allowed: {}",
        allowed.join(", ")
    )
}

/// The law of a run-time closure: named arrays in, named arrays out.
pub trait BatchFunction: Send + Sync {
    /// Evaluate with `params` (the values of [`RuntimeModel::params`], in order) on
    /// `inputs` (one slice per input name of [`io`], all of one length), writing
    /// `outputs`: one slice per output name of [`io`], then possibly slices for the first
    /// [`optional_outputs`], each of the inputs' length. Returns how many of `outputs` it
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
}

impl RuntimeLimit {
    /// The limit at parameter values `values`.
    pub fn at(self, values: &[f64]) -> Limit {
        let value = |i: usize| values.get(i).copied().unwrap_or(f64::NAN);
        match self {
            RuntimeLimit::Fixed(l) => l,
            RuntimeLimit::StokesParam(i) => Limit::Stokes { cd_re: value(i) },
            RuntimeLimit::EinsteinParam(i) => Limit::Einstein { coefficient: value(i) },
        }
    }
}

/// A run-time closure as built: the family trait object.
pub enum Built {
    /// a drag law
    Drag(Box<dyn DragLaw>),
    /// a hindrance
    Hindrance(Box<dyn Hindrance>),
    /// an effective viscosity
    Viscosity(Box<dyn EffectiveViscosity>),
    /// a side-wall friction law
    WallFriction(Box<dyn WallFriction>),
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

from_runtime!(DragLaw => Drag, Hindrance => Hindrance, EffectiveViscosity => Viscosity, WallFriction => WallFriction; GranularStress, Turbulence, Fluctuation);

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
    /// the law
    pub function: Arc<dyn BatchFunction>,
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
/// family outside [`FAMILIES`], a name that is not a plain identifier or that a compiled
/// model of the family carries, parameter names repeated or `type`, a default outside its
/// range.
pub fn register(model: RuntimeModel) -> Result<(), String> {
    let (family, name) = (model.family, model.name);
    if io(family).is_none() {
        return Err(refused(family));
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
        if let RuntimeLimit::StokesParam(i) | RuntimeLimit::EinsteinParam(i) = l {
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
