//! The declarative scene: one TOML file with the physics, the grains, the shared
//! column, the closures (one table per family, `type = "..."` plus parameters), the
//! solver with the numerics of both solvers, and the output.
//!
//! Loading is done in stages so that every error names the file and the full key path:
//! TOML syntax (line and column) -> tables where tables are expected -> the
//! `accuracy` preset's keys where the scene gives none ([`Accuracy`]) -> base tables
//! (serde_path_to_error) -> ranges of every key -> each closure table on its own (model
//! name checked against the registry first, parameters with their full path) -> derived
//! defaults -> closure needs -> what the active solver needs. `saltus check` and
//! `saltus run` both go through [`Scene::from_file_with`], so they refuse the same
//! scenes.

mod closures;
mod closures_file;
mod consistency;
mod domain;
mod forcing;
pub mod initial;
mod lagrangian;
mod overrides;
mod presets;
mod python;
pub mod shields;
mod solver;
mod tables;

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::closure::Family;
use crate::error::{Error, Result};
use crate::needs::{Field, Needs};
use crate::param::ParamRange;

pub use closures::{closure_from_value, de_concrete, granular_from_value, Closures, DEFAULT_MODELS};
pub use closures_file::{apply_closures_file, closures_file_tables, CLOSURES_FILE_KEYS};
pub use domain::{CellSize, Domain, Top, CELLS_PER_DIAMETER, MAX_CELLS, MAX_HEIGHT, MAX_STRETCH_DECADES};
pub use forcing::{Forcing, Quantity, Signal};
pub use lagrangian::{
    Case, DragVelocity, PhiAverage, CELL_DIAMETERS, FLUID_CELLS_PER_DIAMETER, FREY_LEVELS, MAX_FLUID_CELLS,
    MAX_PARTICLES, MAX_PHI_DIFFUSION, MAX_SIDE_DIAMETERS,
};
pub use overrides::{apply_override, parse_table, FACES};
pub use presets::{Accuracy, Preset};
pub use python::Python;
pub use solver::{
    default_elastic_phi_rlp, Bottom, EulerianSettings, FluidMode, Initial, LagrangianSettings, ParticleSpec, Solver,
    SolverKind, Surface, TimeStepping, ELASTIC_PHI_RLP,
};
use tables::STIFFNESS;
pub use tables::{
    Contact, ContactModel, Drive, Fluid, Meta, NormalForce, Output, Particles, Physics, Reference, ShieldsWeight,
    TangentialHistory, MAX_PHASES, MAX_SNAPSHOTS, MAX_TIMESERIES_ROWS, TIMESERIES_ROWS,
};

/// Longest simulated time of either solver (s): about 30 years, a bound that keeps
/// step counts and times finite.
pub const MAX_TIME: f64 = 1.0e9;

/// An [`Error::Key`] at `key` of `file`.
pub(crate) fn key_error(file: &Path, key: &str, message: impl Into<String>) -> Error {
    Error::Key { file: file.into(), key: key.into(), message: message.into() }
}

/// Packing the DEM counts the particles of a bed with when `domain.bed_phi` is absent.
pub const DEM_BED_PHI: f64 = 0.6;
/// Packing of the Eulerian initial bed when `domain.bed_phi` is absent (Chassagne 2023),
/// unless above 0.95 of the closure's maximum packing.
pub const EULERIAN_BED_PHI: f64 = 0.61;

/// A loaded, resolved and checked scene.
#[derive(Debug, Serialize)]
pub struct Scene {
    /// description
    pub meta: Meta,
    /// random seed of every stochastic stream
    pub seed: u64,
    /// the preset of the numerical defaults the scene chose ([`Accuracy`]); `None` when
    /// it chose none (the defaults, as `"standard"`)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<Accuracy>,
    /// fluid
    pub fluid: Fluid,
    /// particles
    pub particles: Particles,
    /// body forces
    pub physics: Physics,
    /// the column both solvers share
    pub domain: Domain,
    /// the active solver and the numerics of both
    pub solver: Solver,
    /// closures
    pub closures: Closures,
    /// output
    pub output: Output,
    /// reference data, in the order of the scene file, paths absolute
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reference: Vec<Reference>,
    /// the Python files or modules registering the scene's closures, files absolute
    #[serde(skip_serializing_if = "Option::is_none")]
    pub python: Option<Python>,
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
    domain: Domain,
    #[serde(default)]
    solver: Solver,
    #[serde(default)]
    output: Output,
}

/// Keys that must hold a table. serde reads a struct from an array too (by position), so
/// `particles = [1, 2]` would load as 1 m grains; refuse it before.
const TABLE_KEYS: [&str; 12] = [
    "meta",
    "fluid",
    "particles",
    "particles.contact",
    "physics",
    "domain",
    "solver",
    "solver.eulerian",
    "solver.lagrangian",
    "output",
    "closures",
    "closures.granular",
];

fn require_tables(table: &toml::Table, file: &Path) -> Result<()> {
    for key in TABLE_KEYS {
        let mut here = Some(table);
        let mut value = None;
        for seg in key.split('.') {
            value = here.and_then(|t| t.get(seg));
            here = value.and_then(|v| v.as_table());
        }
        if let Some(v) = value.filter(|v| !v.is_table()) {
            return Err(Error::Key {
                file: file.into(),
                key: key.into(),
                message: format!("expected a table ([{key}] or {key} = {{ ... }}), found {}", v.type_str()),
            });
        }
    }
    Ok(())
}

/// Serialise any value (a closure trait object included) to a TOML string.
pub fn to_toml_table<T: Serialize + ?Sized>(v: &T) -> std::result::Result<String, String> {
    toml::to_string(v).map_err(|e| e.to_string())
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
        Error::Key { file: file.to_path_buf(), key, message: e.into_inner().message().trim().to_string() }
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
            value: crate::param::number(value),
            allowed: range.to_string(),
        })
    }
}

impl Scene {
    /// Read, resolve and check a scene file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene> {
        Self::from_file_with(path, &[])
    }

    /// The `[python] modules` of a scene file with its overrides, resolved as a load
    /// resolves them (files absolute), read before anything else of the scene: what the
    /// Python package imports before it loads the scene.
    pub fn python_modules(path: impl AsRef<Path>, overrides: &[String]) -> Result<Vec<String>> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io { file: path.into(), source })?;
        let mut table = parse_table(&text, path)?;
        for o in overrides {
            apply_override(&mut table, o)?;
        }
        match table.remove("python") {
            Some(v) => Ok(Python::from_value(v, path)?.modules),
            None => Ok(Vec::new()),
        }
    }

    /// Read a scene file and apply `--set KEY=VALUE` overrides before resolving it.
    pub fn from_file_with(path: impl AsRef<Path>, overrides: &[String]) -> Result<Scene> {
        Self::from_file_with_closures(path, overrides, None)
    }

    /// [`Scene::from_file_with`] with the `[closures.<family>]` tables of closures file
    /// `closures` (`saltus run --closures FILE`) in place of the scene's, family by
    /// family, before the overrides; the file is recorded in `meta.closures_file`. An
    /// error inside a table of the file names the file.
    pub fn from_file_with_closures(
        path: impl AsRef<Path>,
        overrides: &[String],
        closures: Option<&Path>,
    ) -> Result<Scene> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io { file: path.into(), source })?;
        let mut table = parse_table(&text, path)?;
        let families = match closures {
            Some(c) => closures_file::apply_closures_file(&mut table, c)?,
            None => Vec::new(),
        };
        for o in overrides {
            apply_override(&mut table, o)?;
        }
        let scene = Self::from_table(table, path);
        match closures {
            Some(c) => scene.map_err(|e| closures_file::attribute(e, c, &families)),
            None => scene,
        }
    }

    /// Resolve and check a scene given as a TOML table (`file` is used in messages and
    /// to resolve reference paths).
    pub fn from_table(mut table: toml::Table, file: &Path) -> Result<Scene> {
        require_tables(&table, file)?;
        // the preset's keys go in where the scene gives none, so that the scene's win
        let accuracy = Accuracy::take(&mut table, file)?;
        if let Some(a) = accuracy {
            a.apply(&mut table);
        }
        let python = table.remove("python").map(|v| Python::from_value(v, file)).transpose()?;
        // before the closures: their names are registered by the modules
        if let Some(p) = python.as_ref().filter(|_| !crate::runtime::python_host()) {
            return Err(p.refused(file));
        }
        let closures_value = table.remove("closures");
        let given = shields::Given::of(&table);
        let reference_value = table.remove("reference");
        let forcing_value = table.get_mut("physics").and_then(|p| p.as_table_mut()).and_then(|p| p.remove("forcing"));
        let mut base: Base = de_path(toml::Value::Table(table), file, "")?;
        base.physics.forcing = forcing_value.map(|v| Forcing::from_value(v, file)).transpose()?;
        let reference = tables::references(reference_value, file)?;
        base.fluid.check(file)?;
        base.particles.check(file)?;
        shields::resolve(&mut base.physics, &mut base.domain, &base.fluid, &base.particles, given, file)?;
        base.physics.check(file)?;
        base.domain.check(file)?;
        base.solver.eulerian.check(file)?;
        base.solver.lagrangian.check(file, base.particles.diameter)?;
        let closures = Closures::load_faces(closures_value, &mut base.solver, &base.particles, file)?;
        let mut scene = Scene {
            meta: base.meta,
            seed: base.seed,
            accuracy,
            fluid: base.fluid,
            particles: base.particles,
            physics: base.physics,
            domain: base.domain,
            solver: base.solver,
            closures,
            output: base.output,
            reference,
            python,
            path: file.to_path_buf(),
        };
        scene.resolve()?;
        // a closure registered at run time that failed while the scene resolved (a
        // granular law's jammed packing): its message, not that of the NaN it gave
        if let Some(message) = scene.closures.failure() {
            let family = message.split_whitespace().next().and_then(Family::from_key);
            let key = family.map_or_else(|| "closures".to_string(), |f| format!("closures.{f}"));
            return Err(Error::Key { file: file.into(), key, message });
        }
        scene.check_needs()?;
        scene.check_active()?;
        Ok(scene)
    }

    /// What the DEM's derived defaults depend on.
    pub fn case(&self) -> Case {
        Case {
            d: self.particles.diameter,
            rho_p: self.particles.density,
            rho_f: self.fluid.density,
            gravity: self.physics.gravity,
            bed_height: self.domain.bed_height,
            water_depth: self.domain.water_depth,
            bed_phi: self.domain.bed_phi.unwrap_or(DEM_BED_PHI),
        }
    }

    /// Fill every default that depends on the case, so that the resolved scene holds the
    /// numbers used: cells, the bed packing of the active solver, the DEM's box, fluid
    /// cells and settle time, the stiffness, absolute reference paths.
    fn resolve(&mut self) -> Result<()> {
        let d = self.particles.diameter;
        if let Some(size) = self.domain.cell_size {
            self.resolve_cell_size(size.metres(d))?;
        }
        let accuracy = self.accuracy.unwrap_or_default();
        if self.domain.cells.is_none() {
            let n = accuracy.eulerian_cells(&self.domain, d).unwrap_or_else(|| self.domain.default_cells(d));
            // a default over the cap is left out, refused below only if the Eulerian runs
            self.domain.cells = (n <= MAX_CELLS).then_some(n);
        }
        let case = self.case();
        if self.solver.lagrangian.cells.is_none() {
            self.solver.lagrangian.cells = accuracy.fluid_cells(case.bed_height + case.water_depth, d);
        }
        self.solver.lagrangian.resolve(&case);
        if self.particles.contact.stiffness.is_none() {
            let dry = self.solver.lagrangian.fluid == FluidMode::Off;
            let rho_f = if dry { 0.0 } else { self.fluid.density };
            // a default beyond the range of the key is left out, as one that cannot be derived
            self.particles.contact.stiffness = self
                .particles
                .rigid_stiffness(rho_f, self.physics.gravity, case.bed_phi, case.bed_height)
                .filter(|k| STIFFNESS.contains(*k));
        }
        if self.domain.bed_phi.is_none() {
            self.domain.bed_phi = match self.solver.kind {
                SolverKind::Lagrangian => Some(DEM_BED_PHI),
                SolverKind::Eulerian => self.closures.max_packing().map(|m| {
                    if EULERIAN_BED_PHI < 0.95 * m {
                        EULERIAN_BED_PHI
                    } else {
                        0.95 * m
                    }
                }),
            };
        }
        let (end_time, _) = self.end_time();
        self.output.resolve(end_time);
        if self.solver.eulerian.elastic_phi_rlp.is_none() {
            self.solver.eulerian.elastic_phi_rlp = self.closures.max_packing().map(solver::default_elastic_phi_rlp);
        }
        let dir = self.path.parent().map(Path::to_path_buf).unwrap_or_default();
        for r in &mut self.reference {
            r.file = absolute(&dir, &r.file);
        }
        if let Some(csv) = &mut self.domain.initial_profiles {
            if self.solver.kind == SolverKind::Lagrangian {
                return Err(Error::Key {
                    file: self.path.clone(),
                    key: initial::KEY.into(),
                    message: "the Eulerian column's start; the DEM starts from rest or from another run's grains"
                        .into(),
                });
            }
            *csv = absolute(&dir, csv);
            self.domain.initial_columns = initial::read(Path::new(csv.as_str()), &self.path)?;
        }
        Ok(())
    }

    /// `cells` (and the DEM's fluid cells when not given) of a uniform grid of cells of
    /// `size` m; a `cells` given with it must be that number.
    fn resolve_cell_size(&mut self, size: f64) -> Result<()> {
        let f = self.path.as_path();
        let n = self.domain.cells_of(size, 4);
        if n > MAX_CELLS {
            return Err(Error::Key {
                file: f.into(),
                key: "domain.cell_size".into(),
                message: format!(
                    "{} m over a column of {} m makes more than {MAX_CELLS} cells; give a larger size",
                    crate::param::number(size),
                    crate::param::number(self.domain.height())
                ),
            });
        }
        match self.domain.cells {
            Some(c) if c != n => {
                return Err(Error::Key {
                    file: f.into(),
                    key: "domain.cells".into(),
                    message: format!("= {c}, but domain.cell_size makes {n} cells over the column; remove one of them"),
                })
            }
            _ => self.domain.cells = Some(n),
        }
        if self.solver.kind == SolverKind::Lagrangian && self.solver.lagrangian.cells.is_none() {
            // at most MAX_CELLS (checked above), below the DEM's own cap
            self.solver.lagrangian.cells = Some(self.domain.cells_of(size, 2));
        }
        Ok(())
    }

    /// The scene's name in messages, figures and output folders: `meta.name`, else the
    /// file's stem, else `run`.
    pub fn label(&self) -> String {
        if !self.meta.name.is_empty() {
            return self.meta.name.clone();
        }
        self.path.file_stem().map_or_else(|| "run".into(), |x| x.to_string_lossy().into_owned())
    }

    /// End time of the active solver's run (s), with its key.
    pub fn end_time(&self) -> (f64, &'static str) {
        match self.solver.kind {
            SolverKind::Eulerian => (self.solver.eulerian.end_time, "solver.eulerian.end_time"),
            SolverKind::Lagrangian => (self.solver.lagrangian.end_time, "solver.lagrangian.end_time"),
        }
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

/// `file` relative to `dir` (the scene's folder), made absolute and free of `..` when it
/// exists, so that a resolved scene finds it from any folder.
fn absolute(dir: &Path, file: &str) -> String {
    let p = dir.join(file);
    let p = if p.is_relative() { std::env::current_dir().map(|c| c.join(&p)).unwrap_or(p) } else { p };
    p.canonicalize().unwrap_or(p).display().to_string()
}

impl Fluid {
    fn check(&self, f: &Path) -> Result<()> {
        check(f, "fluid.density", self.density, ParamRange::closed(1e-3, 1e5))?;
        check(f, "fluid.viscosity", self.viscosity, ParamRange::closed(1e-9, 1e3))
    }
}

impl Physics {
    fn check(&self, f: &Path) -> Result<()> {
        check(f, "physics.gravity", self.gravity, ParamRange::closed(0.0, 1e3))?;
        check(f, "physics.slope", self.slope, ParamRange::closed(-1.0, 1.0))?;
        check(f, "physics.pressure_gradient", self.pressure_gradient, ParamRange::closed(-1e9, 1e9))?;
        if self.forcing.is_some() && self.shields.is_some() {
            return Err(Error::Key {
                file: f.into(),
                key: "physics.forcing".into(),
                message: "with physics.shields: a Shields number sets a steady driving; give the driving by physics.pressure_gradient or physics.slope with a forcing".into(),
            });
        }
        Ok(())
    }
}
