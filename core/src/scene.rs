//! The declarative scene: one TOML file with the physics, the closures (one table per
//! family, `type = "..."` plus parameters), the solver and its numerics, and the output.
//!
//! Loading is done in stages so that every error names the file and the full key path:
//! TOML syntax (line and column) -> base tables (serde_path_to_error) -> each closure
//! table on its own (model name checked against the registry first) -> parameter ranges
//! -> closure needs.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::closure::Family;
use crate::error::{Error, Result};
use crate::needs::{Field, Needs};
use crate::param::{Describe, ParamRange};
use crate::registry;
use crate::{DragLaw, EffectiveViscosity, Fluctuation, GranularStress, Hindrance, Turbulence};

/// Free-form description.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Meta {
    /// short name, used for output folders
    #[serde(default)]
    pub name: String,
    /// one paragraph
    #[serde(default)]
    pub description: String,
}

/// Carrier fluid.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// density rho_f (kg/m^3)
    #[serde(default = "default_rho_f")]
    pub density: f64,
    /// kinematic viscosity nu_f (m^2/s)
    #[serde(default = "default_nu_f")]
    pub viscosity: f64,
}

fn default_rho_f() -> f64 {
    1000.0
}
fn default_nu_f() -> f64 {
    1.0e-6
}

impl Default for Fluid {
    fn default() -> Self {
        Self { density: default_rho_f(), viscosity: default_nu_f() }
    }
}

/// Grains (monodisperse spheres).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Particles {
    /// diameter d (m)
    pub diameter: f64,
    /// density rho_p (kg/m^3)
    pub density: f64,
}

/// Body forces.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Physics {
    /// gravity (m/s^2)
    #[serde(default = "default_g")]
    pub gravity: f64,
    /// bed slope sin(alpha)
    #[serde(default)]
    pub slope: f64,
    /// imposed streamwise pressure gradient -dp/dx (Pa/m)
    #[serde(default)]
    pub pressure_gradient: f64,
}

fn default_g() -> f64 {
    crate::G
}

impl Default for Physics {
    fn default() -> Self {
        Self { gravity: crate::G, slope: 0.0, pressure_gradient: 0.0 }
    }
}

/// Output settings.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// output folder; `out/<meta.name>` when absent
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir: Option<String>,
}

/// Reference data overlaid on the run's plots: `[reference]` for one file, or
/// `[[reference]]` for several (a velocity file and a concentration file, say).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Reference {
    /// whitespace- or comma-separated columns file, relative to the scene file
    pub file: String,
    /// column names of the file, in order
    pub columns: Vec<String>,
    /// added to the file's `z` column (m), for data measured from another origin (from the
    /// bed surface instead of the bottom of the column, say)
    #[serde(default, skip_serializing_if = "is_zero")]
    pub z_offset: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// `[reference]` (one table) or `[[reference]]` (an array of tables). Each table is read
/// on its own so that a mistake is reported with its key and index, not as "no variant
/// matched".
fn one_or_many<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Vec<Reference>, D::Error> {
    use serde::de::Error as _;
    let one = |v: toml::Value, key: String| {
        Reference::deserialize(v).map_err(|e| D::Error::custom(format!("{key}: {}", e.message())))
    };
    match Option::<toml::Value>::deserialize(d)? {
        None => Ok(Vec::new()),
        Some(v @ toml::Value::Table(_)) => Ok(vec![one(v, "reference".into())?]),
        Some(toml::Value::Array(items)) => {
            items.into_iter().enumerate().map(|(i, v)| one(v, format!("reference[{i}]"))).collect()
        }
        Some(other) => Err(D::Error::custom(format!(
            "reference: expected a table ([reference]) or an array of tables ([[reference]]), found {}",
            other.type_str()
        ))),
    }
}

/// The closures of a scene, one per family. Absent families take their defaults when the
/// scene is resolved (see [`DEFAULT_MODELS`]); `granular` has no default.
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
}

/// Default model of each family (none for `granular`).
pub const DEFAULT_MODELS: [(Family, &str); 5] = [
    (Family::Drag, "dallavalle"),
    (Family::Hindrance, "richardson_zaki"),
    (Family::Viscosity, "clear_fluid"),
    (Family::Turbulence, "laminar"),
    (Family::Fluctuation, "none"),
];

/// A loaded, resolved and checked scene.
#[derive(Debug, Serialize)]
pub struct Scene {
    /// description
    pub meta: Meta,
    /// random seed of every stochastic stream
    pub seed: u64,
    /// fluid
    pub fluid: Fluid,
    /// particles
    pub particles: Particles,
    /// body forces
    pub physics: Physics,
    /// domain (solver-specific, checked by the solver)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub domain: Option<toml::Table>,
    /// solver and numerics (solver-specific, checked by the solver)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solver: Option<toml::Table>,
    /// closures
    pub closures: Closures,
    /// output
    pub output: Output,
    /// reference data, in the order of the scene file
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reference: Vec<Reference>,
    /// file the scene was read from (for messages and relative paths)
    #[serde(skip)]
    pub path: PathBuf,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Base {
    #[serde(default)]
    meta: Meta,
    #[serde(default)]
    seed: u64,
    #[serde(default)]
    fluid: Fluid,
    particles: Particles,
    #[serde(default)]
    physics: Physics,
    #[serde(default)]
    domain: Option<toml::Table>,
    #[serde(default)]
    solver: Option<toml::Table>,
    #[serde(default)]
    output: Output,
    #[serde(default, deserialize_with = "one_or_many")]
    reference: Vec<Reference>,
}

/// Serialise any value (a closure trait object included) to a TOML string.
pub fn to_toml_table<T: Serialize + ?Sized>(v: &T) -> std::result::Result<String, String> {
    toml::to_string(v).map_err(|e| e.to_string())
}

/// Parse TOML text into a table; syntax errors carry line and column.
pub fn parse_table(text: &str, file: &Path) -> Result<toml::Table> {
    text.parse::<toml::Table>().map_err(|e| {
        let (line, column) = e.span().map(|s| line_col(text, s.start)).unwrap_or((0, 0));
        Error::Syntax { file: file.to_path_buf(), line, column, message: e.message().to_string() }
    })
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    // spans are byte offsets; fall back to the whole text rather than slice mid-character
    let before = text.get(..offset.min(text.len())).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Deserialise `value` found at key path `prefix` of `file` into `T`, reporting the full
/// key path of a missing, unknown or mistyped key. Solvers use it for their `[domain]`
/// and `[solver]` tables.
pub fn de_path<T: DeserializeOwned>(value: toml::Value, file: &Path, prefix: &str) -> Result<T> {
    serde_path_to_error::deserialize::<_, T>(value).map_err(|e| {
        let inner = e.path().to_string();
        let key = match (prefix.is_empty(), inner == ".") {
            (true, _) => inner,
            (false, true) => prefix.to_string(),
            (false, false) => format!("{prefix}.{inner}"),
        };
        Error::Key { file: file.to_path_buf(), key, message: e.into_inner().to_string() }
    })
}

/// The solver-specific `[domain]` (required; `needs` says what it must hold when it is
/// missing) and `[solver]` (optional, defaults) tables of `scene`, typed, with errors that
/// name the file and the full key.
pub fn domain_and_solver<D: DeserializeOwned, S: DeserializeOwned>(scene: &Scene, needs: &str) -> Result<(D, S)> {
    let file = scene.path.as_path();
    let domain_table = scene.domain.clone().ok_or_else(|| Error::Key {
        file: file.into(),
        key: "domain".into(),
        message: format!("missing table; {needs}"),
    })?;
    let domain = de_path(toml::Value::Table(domain_table), file, "domain")?;
    let settings = de_path(toml::Value::Table(scene.solver.clone().unwrap_or_default()), file, "solver")?;
    Ok((domain, settings))
}

/// Deserialise one closure table of family `family` found at key path `key`. The model
/// name is checked against the registry first so that an unknown name lists the known
/// ones, and the parameters are range-checked.
pub fn closure_from_value<T>(value: toml::Value, family: Family, file: &Path, key: &str) -> Result<Box<T>>
where
    T: ?Sized + Describe,
    Box<T>: DeserializeOwned,
{
    let table = match &value {
        toml::Value::Table(t) => t,
        other => {
            return Err(Error::Key {
                file: file.into(),
                key: key.into(),
                message: format!(
                    "expected a table such as {{ type = \"{}\" }}, found {}",
                    registry::models_of(family).first().map_or("...", |m| m.name),
                    other.type_str()
                ),
            })
        }
    };
    let name = match table.get("type") {
        Some(toml::Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(Error::Key {
                file: file.into(),
                key: format!("{key}.type"),
                message: format!("expected a model name (string), found {}", other.type_str()),
            })
        }
        None => {
            return Err(Error::Key {
                file: file.into(),
                key: format!("{key}.type"),
                message: format!("missing; known {family} models: {}", registry::known_names(family)),
            })
        }
    };
    if !registry::models_of(family).iter().any(|m| m.name == name) {
        return Err(Error::UnknownModel {
            file: file.into(),
            key: format!("{key}.type"),
            family: family.to_string(),
            name,
            known: registry::known_names(family),
        });
    }
    let model: Box<T> = de_path(value, file, key)?;
    model.validate().map_err(|e| Error::from_param(file, key, e))?;
    Ok(model)
}

fn default_closure<T>(family: Family, file: &Path) -> Result<Box<T>>
where
    T: ?Sized + Describe,
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

/// An [`Error::OutOfRange`] naming `file` and `key` unless `range` contains `value`.
pub fn check(file: &Path, key: &str, value: f64, range: ParamRange) -> Result<()> {
    if range.contains(value) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            file: file.into(),
            key: key.into(),
            value: value.to_string(),
            allowed: range.to_string(),
        })
    }
}

impl Scene {
    /// Read, resolve and check a scene file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene> {
        Self::from_file_with(path, &[])
    }

    /// Read a scene file and apply `--set KEY=VALUE` overrides before resolving it.
    pub fn from_file_with(path: impl AsRef<Path>, overrides: &[String]) -> Result<Scene> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io { file: path.into(), source })?;
        let mut table = parse_table(&text, path)?;
        for o in overrides {
            apply_override(&mut table, o)?;
        }
        Self::from_table(table, path)
    }

    /// Resolve and check a scene given as a TOML table (`file` is used in messages).
    pub fn from_table(mut table: toml::Table, file: &Path) -> Result<Scene> {
        let closures_value = table.remove("closures");
        let base: Base = de_path(toml::Value::Table(table), file, "")?;
        let closures = Self::closures(closures_value, file)?;
        let scene = Scene {
            meta: base.meta,
            seed: base.seed,
            fluid: base.fluid,
            particles: base.particles,
            physics: base.physics,
            domain: base.domain,
            solver: base.solver,
            closures,
            output: base.output,
            reference: base.reference,
            path: file.to_path_buf(),
        };
        scene.check()?;
        Ok(scene)
    }

    fn closures(value: Option<toml::Value>, file: &Path) -> Result<Closures> {
        let mut table = match value {
            None => toml::Table::new(),
            Some(toml::Value::Table(t)) => t,
            Some(other) => {
                return Err(Error::Key {
                    file: file.into(),
                    key: "closures".into(),
                    message: format!("expected a table, found {}", other.type_str()),
                })
            }
        };
        let mut c = Closures::default();
        let mut take = |f: Family| table.remove(f.key()).map(|v| (v, format!("closures.{}", f.key())));
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
            c.granular = Some(closure_from_value(v, Family::Granular, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Turbulence) {
            c.turbulence = Some(closure_from_value(v, Family::Turbulence, file, &k)?);
        }
        if let Some((v, k)) = take(Family::Fluctuation) {
            c.fluctuation = Some(closure_from_value(v, Family::Fluctuation, file, &k)?);
        }
        if let Some(k) = table.keys().next() {
            let known: Vec<_> = Family::ALL.iter().map(|f| f.key()).collect();
            return Err(Error::Key {
                file: file.into(),
                key: format!("closures.{k}"),
                message: format!("unknown closure family; known: {}", known.join(", ")),
            });
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

    /// Physical ranges of the base tables and closure needs.
    fn check(&self) -> Result<()> {
        let f = self.path.as_path();
        check(f, "fluid.density", self.fluid.density, ParamRange::positive())?;
        check(f, "fluid.viscosity", self.fluid.viscosity, ParamRange::positive())?;
        check(f, "particles.diameter", self.particles.diameter, ParamRange::positive())?;
        check(f, "particles.density", self.particles.density, ParamRange::positive())?;
        check(f, "physics.gravity", self.physics.gravity, ParamRange::non_negative())?;
        check(f, "physics.slope", self.physics.slope, ParamRange::closed(-1.0, 1.0))?;
        check(f, "physics.pressure_gradient", self.physics.pressure_gradient, ParamRange::any())?;
        self.check_needs()
    }

    /// Fields provided by the scene's closures.
    pub fn provided(&self) -> Needs {
        let mut p = Needs::NONE;
        if let Some(t) = &self.closures.turbulence {
            p = p.union(t.provides());
        }
        if let Some(g) = &self.closures.granular {
            p = p.union(g.provides());
        }
        p
    }

    fn check_needs(&self) -> Result<()> {
        let provided = self.provided();
        if let Some(fl) = &self.closures.fluctuation {
            if let Some(field) = fl.needs().missing(provided).next() {
                let turb = self.closures.turbulence.as_ref().map_or("none", |t| t.name());
                return Err(Error::UnmetNeed {
                    file: self.path.clone(),
                    key: "closures.fluctuation".into(),
                    model: fl.name().into(),
                    field: field.name().into(),
                    provider: provider_sentence(field, turb),
                });
            }
        }
        Ok(())
    }

    /// Resolved scene as TOML text (every default filled in).
    pub fn to_toml(&self) -> Result<String> {
        toml::to_string(self).map_err(|e| Error::Invalid(format!("cannot serialise scene: {e}")))
    }

    /// Submerged density ratio s - 1 = rho_p / rho_f - 1.
    pub fn submerged_ratio(&self) -> f64 {
        self.particles.density / self.fluid.density - 1.0
    }
}

fn provider_sentence(field: Field, turbulence: &str) -> String {
    match field {
        Field::GranularTemperature => {
            "only a kinetic granular closure provides (closures.granular type = \"frictional_collisional\")".into()
        }
        _ => format!("turbulence model `{turbulence}` (closures.turbulence) does not provide"),
    }
}

/// Apply one `KEY=VALUE` override to a raw scene table. VALUE is parsed as a TOML value
/// (so `0.3`, `"text"`, `{type = "stokes"}` work); a bare word is taken as a string.
pub fn apply_override(table: &mut toml::Table, spec: &str) -> Result<()> {
    let (key, raw) =
        spec.split_once('=').ok_or_else(|| Error::Invalid(format!("--set `{spec}`: expected KEY=VALUE")))?;
    let key = key.trim();
    let raw = raw.trim();
    let value = format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()));
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(Error::Invalid(format!("--set `{spec}`: empty key segment")));
    }
    let mut cur = table;
    for p in &parts[..parts.len() - 1] {
        let entry = cur.entry(p.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(Error::Invalid(format!("--set `{spec}`: `{p}` is not a table"))),
        };
    }
    cur.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syntax_error_has_line_and_column() {
        let e = parse_table("a = 1\nb = = 2\n", Path::new("x.toml")).unwrap_err();
        match e {
            Error::Syntax { line, column, .. } => {
                assert_eq!(line, 2);
                assert!(column >= 3);
            }
            other => panic!("unexpected {other}"),
        }
    }

    #[test]
    fn override_sets_nested_keys_and_tables() {
        let mut t: toml::Table = "[closures.drag]\ntype = \"dallavalle\"\n".parse().unwrap();
        apply_override(&mut t, "closures.drag={type=\"stokes\"}").unwrap();
        apply_override(&mut t, "physics.slope=0.05").unwrap();
        assert_eq!(t["closures"]["drag"]["type"].as_str(), Some("stokes"));
        assert_eq!(t["physics"]["slope"].as_float(), Some(0.05));
        assert!(apply_override(&mut t, "noequals").is_err());
    }
}
