//! `[closures]`: one table per family, `type = "..."` plus parameters. Each table is
//! read on its own, its model name checked against the registry first, and a mistake
//! inside it reported with its full key path.

use std::path::Path;
use std::sync::Arc;

use serde::de::DeserializeOwned;
use serde::Serialize;

use super::de_path;
use super::solver::{Solver, SolverKind};
use super::tables::Particles;
use crate::closure::Family;
use crate::error::{Error, Result};
use crate::param::Describe;
use crate::registry;
use crate::runtime::{self, FromRuntime, RuntimeModel};
use crate::{DragLaw, EffectiveViscosity, Fluctuation, GranularStress, Hindrance, Turbulence, WallFriction};

/// The closures of a scene, one per family. Absent families take their defaults when the
/// scene is resolved (see [`DEFAULT_MODELS`]); `granular` and `wall_friction` have no default.
#[derive(Debug, Default, Serialize)]
pub struct Closures {
    /// single-particle drag
    pub drag: Option<Box<dyn DragLaw>>,
    /// hindrance
    pub hindrance: Option<Box<dyn Hindrance>>,
    /// effective fluid viscosity
    pub viscosity: Option<Box<dyn EffectiveViscosity>>,
    /// granular stress
    #[serde(skip_serializing_if = "Option::is_none")]
    pub granular: Option<Box<dyn GranularStress>>,
    /// turbulence
    pub turbulence: Option<Box<dyn Turbulence>>,
    /// fluid velocity fluctuations
    pub fluctuation: Option<Box<dyn Fluctuation>>,
    /// friction of the side walls of a narrow channel on the fluid (none: the fluid does
    /// not feel the walls)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_friction: Option<Box<dyn WallFriction>>,
}

/// Default model of each family (none for `granular` and `wall_friction`).
pub const DEFAULT_MODELS: [(Family, &str); 5] = [
    (Family::Drag, "dallavalle"),
    (Family::Hindrance, "richardson_zaki"),
    (Family::Viscosity, "clear_fluid"),
    (Family::Turbulence, "laminar"),
    (Family::Fluctuation, "none"),
];

/// Deserialise a model's parameters (its table without `type`) as the concrete type,
/// returning the key path and message of the first error. typetag buffers the table and
/// loses the path; the registry calls this with the concrete type to recover it.
pub fn de_concrete<T: DeserializeOwned>(value: toml::Value) -> std::result::Result<(), (String, String)> {
    serde_path_to_error::deserialize::<_, T>(value).map(|_| ()).map_err(|e| {
        let path = e.path().to_string();
        (if path == "." { String::new() } else { path }, e.into_inner().message().trim().to_string())
    })
}

/// Deserialise one closure table of family `family` found at key path `key`. The model
/// name is checked against the registry first so that an unknown name lists the known
/// ones, and the parameters are range-checked.
pub fn closure_from_value<T>(value: toml::Value, family: Family, file: &Path, key: &str) -> Result<Box<T>>
where
    T: ?Sized + Describe + FromRuntime,
    Box<T>: DeserializeOwned,
{
    closure_with(value, family, file, key, |_, _| ())
}

impl runtime::Built {
    /// Build `value` (a closure table with its `type`) of `family`, as
    /// [`closure_from_value`] does for that family's trait. Errors name `file` and the key
    /// path under `key`.
    pub fn from_value(family: Family, value: toml::Value, file: &Path, key: &str) -> Result<runtime::Built> {
        use runtime::Built;
        Ok(match family {
            Family::Drag => Built::Drag(closure_from_value(value, family, file, key)?),
            Family::Hindrance => Built::Hindrance(closure_from_value(value, family, file, key)?),
            Family::Viscosity => Built::Viscosity(closure_from_value(value, family, file, key)?),
            Family::Granular => Built::Granular(closure_from_value(value, family, file, key)?),
            Family::Turbulence => Built::Turbulence(closure_from_value(value, family, file, key)?),
            Family::Fluctuation => Built::Fluctuation(closure_from_value(value, family, file, key)?),
            Family::WallFriction => Built::WallFriction(closure_from_value(value, family, file, key)?),
        })
    }

    /// The model as its TOML table (with `type`), as a scene would hold it.
    pub fn to_toml(&self) -> std::result::Result<String, String> {
        use runtime::Built;
        match self {
            Built::Drag(m) => super::to_toml_table(m),
            Built::Hindrance(m) => super::to_toml_table(m),
            Built::Viscosity(m) => super::to_toml_table(m),
            Built::WallFriction(m) => super::to_toml_table(m),
            Built::Granular(m) => super::to_toml_table(m),
            Built::Turbulence(m) => super::to_toml_table(m),
            Built::Fluctuation(m) => super::to_toml_table(m),
        }
    }
}

/// A granular closure table found at key path `key` of `file`, built as a scene builds
/// `[closures.granular]`: what it does not set (restitution, friction) is inherited from
/// `particles` before the range check.
pub fn granular_from_value(
    value: toml::Value,
    particles: &Particles,
    file: &Path,
    key: &str,
) -> Result<Box<dyn GranularStress>> {
    closure_with(value, Family::Granular, file, key, |m: &mut Box<dyn GranularStress>, t| {
        m.inherit(t, &particles.grains())
    })
}

/// [`closure_from_value`] with `prepare` called on the model and its table between
/// deserialisation and the range check (a granular closure inherits the grain's
/// properties there).
fn closure_with<T>(
    value: toml::Value,
    family: Family,
    file: &Path,
    key: &str,
    prepare: impl FnOnce(&mut Box<T>, &toml::Table),
) -> Result<Box<T>>
where
    T: ?Sized + Describe + FromRuntime,
    Box<T>: DeserializeOwned,
{
    let key_err = |k: String, message: String| Error::Key { file: file.into(), key: k, message };
    let table = match &value {
        toml::Value::Table(t) => t.clone(),
        other => {
            return Err(key_err(
                key.into(),
                format!(
                    "expected a table such as {{ type = \"{}\" }}, found {}",
                    registry::models_of(family).first().map_or("...", |m| m.name),
                    other.type_str()
                ),
            ))
        }
    };
    let name = match table.get("type") {
        Some(toml::Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(key_err(
                format!("{key}.type"),
                format!("expected a model name (string), found {}", other.type_str()),
            ))
        }
        None => {
            return Err(key_err(
                format!("{key}.type"),
                format!("missing; known {family} models: {}", runtime::known_names(family)),
            ))
        }
    };
    let Some(entry) = registry::models_of(family).into_iter().find(|m| m.name == name) else {
        if let Some(model) = runtime::lookup(family, &name) {
            let mut m = runtime_closure(&model, &table, file, key)?;
            prepare(&mut m, &table);
            return Ok(m);
        }
        return Err(Error::UnknownModel {
            file: file.into(),
            key: format!("{key}.type"),
            family: family.to_string(),
            name,
            known: runtime::known_names(family),
        });
    };
    let mut params = table.clone();
    params.remove("type");
    // serde reads a struct from an array too (by position): compare with the shape of
    // the model's default, where every sub-table is a table
    if let Ok(Ok(default)) = (entry.default_toml)().map(|t| t.parse::<toml::Table>()) {
        if let Some((path, found)) = array_for_table(&params, &default) {
            return Err(key_err(format!("{key}.{path}"), format!("expected a table, found {found}")));
        }
    }
    if let Err((path, message)) = (entry.check_toml)(toml::Value::Table(params.clone())) {
        let inner = refine(&params, &path, &message);
        let full = if inner.is_empty() { key.to_string() } else { format!("{key}.{inner}") };
        return Err(key_err(full, message));
    }
    let mut model: Box<T> = de_path(value, file, key)?;
    prepare(&mut model, &table);
    model.validate().map_err(|e| Error::from_param(file, key, e))?;
    Ok(model)
}

/// A closure registered at run time, from its table at key path `key`: every key one of
/// its declared parameters (a number), each within its declared range, then built. The
/// messages are those of compiled models (serde's for an unknown key).
fn runtime_closure<T>(model: &Arc<RuntimeModel>, table: &toml::Table, file: &Path, key: &str) -> Result<Box<T>>
where
    T: ?Sized + Describe + FromRuntime,
{
    let key_err = |k: String, message: String| Error::Key { file: file.into(), key: k, message };
    let mut values: Vec<f64> = model.params.iter().map(|p| p.value).collect();
    for (k, v) in table.iter().filter(|(k, _)| *k != "type") {
        let Some(i) = model.params.iter().position(|p| p.name == *k) else {
            let known: Vec<String> = model.params.iter().map(|p| format!("`{}`", p.name)).collect();
            let expected = if known.is_empty() {
                "there are no fields".to_string()
            } else {
                format!("expected one of {}", known.join(", "))
            };
            return Err(key_err(format!("{key}.{k}"), format!("unknown field `{k}`, {expected}")));
        };
        values[i] = match v {
            toml::Value::Float(x) => *x,
            // integers are read as reals, as serde reads them into an f64 field
            toml::Value::Integer(n) => *n as f64,
            other => {
                return Err(key_err(format!("{key}.{k}"), format!("expected a number, found {}", other.type_str())))
            }
        };
    }
    model.check_values(&values).map_err(|e| Error::from_param(file, key, e))?;
    let built = (model.build)(model, values).map_err(|m| key_err(format!("{key}.type"), m))?;
    let m = T::from_runtime(built).ok_or_else(|| {
        Error::Invalid(format!("{}: key `{key}`: `{}` was registered for another family", file.display(), model.name))
    })?;
    m.validate().map_err(|e| Error::from_param(file, key, e))?;
    Ok(m)
}

/// The first key of `given` holding something else than a table where `default` holds a
/// table, with the type found.
fn array_for_table(given: &toml::Table, default: &toml::Table) -> Option<(String, &'static str)> {
    given.iter().find_map(|(k, v)| match (v, default.get(k)) {
        (toml::Value::Table(g), Some(toml::Value::Table(d))) => {
            array_for_table(g, d).map(|(path, found)| (format!("{k}.{path}"), found))
        }
        (other, Some(toml::Value::Table(_))) => Some((k.clone(), other.type_str())),
        _ => None,
    })
}

/// Finish a key path that serde stopped short of: inside an internally tagged enum
/// (`g0 = { type = "...", a0 = 1 }`) the path ends at `g0`; the unknown field or variant
/// named by the message is then looked up in that sub-table.
fn refine(params: &toml::Table, path: &str, message: &str) -> String {
    let mut here = params;
    for seg in path.split('.').filter(|s| !s.is_empty()) {
        match here.get(seg) {
            Some(toml::Value::Table(t)) => here = t,
            _ => return path.to_string(),
        }
    }
    let quoted = message.split('`').nth(1).unwrap_or_default();
    let hit = if message.starts_with("unknown field") {
        here.contains_key(quoted).then(|| quoted.to_string())
    } else if message.starts_with("unknown variant") {
        here.iter().find(|(_, v)| v.as_str() == Some(quoted)).map(|(k, _)| k.clone())
    } else if message.starts_with("invalid type") || message.starts_with("invalid value") {
        // serde names the offending value as it found it: `string "x"`, `integer `3``, ...
        let shown = |v: &toml::Value| match v {
            toml::Value::String(s) => Some(format!("string {s:?}")),
            toml::Value::Integer(i) => Some(format!("integer `{i}`")),
            toml::Value::Float(f) => Some(format!("floating point `{f}`")),
            toml::Value::Boolean(b) => Some(format!("boolean `{b}`")),
            _ => None,
        };
        here.iter().find(|(_, v)| shown(v).is_some_and(|t| message.contains(&t))).map(|(k, _)| k.clone())
    } else {
        None
    };
    match (hit, path.is_empty()) {
        (Some(k), true) => k,
        (Some(k), false) => format!("{path}.{k}"),
        (None, _) => path.to_string(),
    }
}

fn default_closure<T>(family: Family, file: &Path) -> Result<Box<T>>
where
    T: ?Sized + Describe + FromRuntime,
    Box<T>: DeserializeOwned,
{
    let name = DEFAULT_MODELS
        .iter()
        .find(|(f, _)| *f == family)
        .map(|(_, n)| *n)
        .ok_or_else(|| Error::Invalid(format!("family {family} has no default model")))?;
    let mut t = toml::Table::new();
    t.insert("type".into(), toml::Value::String(name.into()));
    closure_from_value(toml::Value::Table(t), family, file, &format!("closures.{family}")).map_err(|e| {
        Error::Invalid(format!(
            "default {family} model `{name}` is not registered ({e}); the closures crate was not linked: call saltus_closures::link()"
        ))
    })
}

/// The scene's `[closures]` value as a table (empty when absent).
fn closures_table(value: Option<toml::Value>, file: &Path) -> Result<toml::Table> {
    match value {
        None => Ok(toml::Table::new()),
        Some(toml::Value::Table(t)) => Ok(t),
        Some(other) => Err(Error::Key {
            file: file.into(),
            key: "closures".into(),
            message: format!("expected a table, found {}", other.type_str()),
        }),
    }
}

/// Refuse a key of closure tables `tables` (found at key path `prefix`) that is not a
/// closure family.
fn check_families(tables: &toml::Table, prefix: &str, file: &Path) -> Result<()> {
    match tables.keys().find(|k| Family::from_key(k).is_none()) {
        Some(k) => {
            let known: Vec<_> = Family::ALL.iter().map(|f| f.key()).collect();
            Err(Error::Key {
                file: file.into(),
                key: format!("{prefix}.{k}"),
                message: format!("unknown closure family; known: {}", known.join(", ")),
            })
        }
        None => Ok(()),
    }
}

impl Closures {
    /// The closures of the active solver `solver.kind`: the scene's `[closures]` with the
    /// tables of `[solver.<active>.closures]` in place of the families they hold. The
    /// other solver's face is read and checked as well (so that `check` refuses what a
    /// switch of `solver.type` would), and given, for each family the active face
    /// replaced and it does not hold, the scene's shared table: the resolved scene then
    /// records in `[closures]` what ran and still resolves to the same closures for the
    /// other solver.
    pub(super) fn load_faces(
        value: Option<toml::Value>,
        solver: &mut Solver,
        particles: &Particles,
        file: &Path,
    ) -> Result<Closures> {
        let shared = closures_table(value, file)?;
        check_families(&shared, "closures", file)?;
        check_families(&solver.eulerian.closures, "solver.eulerian.closures", file)?;
        check_families(&solver.lagrangian.closures, "solver.lagrangian.closures", file)?;
        let (active, active_key, other, other_key) = match solver.kind {
            SolverKind::Eulerian => (
                &solver.eulerian.closures,
                "solver.eulerian.closures",
                &mut solver.lagrangian.closures,
                "solver.lagrangian.closures",
            ),
            SolverKind::Lagrangian => (
                &solver.lagrangian.closures,
                "solver.lagrangian.closures",
                &mut solver.eulerian.closures,
                "solver.eulerian.closures",
            ),
        };
        Self::load_with(shared.clone(), other, other_key, particles, file)?;
        for family in active.keys() {
            if other.contains_key(family) {
                continue;
            }
            let table = shared.get(family).cloned().or_else(|| {
                let (_, name) = DEFAULT_MODELS.iter().find(|(f, _)| f.key() == family.as_str())?;
                let mut t = toml::Table::new();
                t.insert("type".into(), toml::Value::String((*name).into()));
                Some(toml::Value::Table(t))
            });
            if let Some(t) = table {
                other.insert(family.clone(), t);
            }
        }
        Self::load_with(shared, active, active_key, particles, file)
    }

    /// The closures of `shared` (the scene's `[closures]`) with those of `face` (found at
    /// key path `face_key`) in place of the families it holds.
    fn load_with(
        mut shared: toml::Table,
        face: &toml::Table,
        face_key: &str,
        particles: &Particles,
        file: &Path,
    ) -> Result<Closures> {
        let mut c = Closures::default();
        let mut take = |f: Family| {
            let own = shared.remove(f.key()).map(|v| (v, format!("closures.{}", f.key())));
            match face.get(f.key()) {
                Some(v) => Some((v.clone(), format!("{face_key}.{}", f.key()))),
                None => own,
            }
        };
        if let Some((v, k)) = take(Family::Drag) {
            c.drag = Some(closure_from_value(v, Family::Drag, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Hindrance) {
            c.hindrance = Some(closure_from_value(v, Family::Hindrance, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Viscosity) {
            c.viscosity = Some(closure_from_value(v, Family::Viscosity, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Granular) {
            let inherit = |m: &mut Box<dyn GranularStress>, t: &toml::Table| m.inherit(t, &particles.grains());
            c.granular = Some(closure_with(v, Family::Granular, file, &k, inherit)?);
        }
        if let Some((v, k)) = take(Family::Turbulence) {
            c.turbulence = Some(closure_from_value(v, Family::Turbulence, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Fluctuation) {
            c.fluctuation = Some(closure_from_value(v, Family::Fluctuation, file, &k)?);
        }
        if let Some((v, k)) = take(Family::WallFriction) {
            c.wall_friction = Some(closure_from_value(v, Family::WallFriction, file, &k)?);
        }
        if c.drag.is_none() {
            c.drag = Some(default_closure(Family::Drag, file)?);
        }
        if c.hindrance.is_none() {
            c.hindrance = Some(default_closure(Family::Hindrance, file)?);
        }
        if c.viscosity.is_none() {
            c.viscosity = Some(default_closure(Family::Viscosity, file)?);
        }
        if c.turbulence.is_none() {
            c.turbulence = Some(default_closure(Family::Turbulence, file)?);
        }
        if c.fluctuation.is_none() {
            c.fluctuation = Some(default_closure(Family::Fluctuation, file)?);
        }
        Ok(c)
    }

    /// The first evaluation error of a closure of the scene ([`Describe::failure`]): a
    /// closure registered at run time whose function raised during a run.
    pub fn failure(&self) -> Option<String> {
        let each: [Option<&dyn Describe>; 7] = [
            self.drag.as_deref().map(|m| m as &dyn Describe),
            self.hindrance.as_deref().map(|m| m as &dyn Describe),
            self.viscosity.as_deref().map(|m| m as &dyn Describe),
            self.granular.as_deref().map(|m| m as &dyn Describe),
            self.turbulence.as_deref().map(|m| m as &dyn Describe),
            self.fluctuation.as_deref().map(|m| m as &dyn Describe),
            self.wall_friction.as_deref().map(|m| m as &dyn Describe),
        ];
        each.into_iter().flatten().find_map(Describe::failure)
    }

    /// Maximum packing of the granular closure (the kinetic phi_max, or the packing of a
    /// local rheology at zero shear); None without one.
    pub fn max_packing(&self) -> Option<f64> {
        let g = self.granular.as_deref()?;
        g.as_kinetic().map(|k| k.phi_max()).or_else(|| g.as_local().map(|l| l.packing(0.0)))
    }
}
