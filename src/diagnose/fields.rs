//! The averaged fields of a run as `diagnose` reads them: `profiles.csv` (empty cells
//! undefined) and the resolved `scene.toml` beside it, for the grain and fluid properties
//! and the scene's closures.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use saltus_core::scene::Scene;
use saltus_core::LocalState;

use crate::run_files;
use crate::table::Table;

/// Profiles and scene of one run's output folder.
pub struct RunFields {
    /// `profiles.csv` of the run (for messages)
    pub profiles_path: PathBuf,
    /// its columns; undefined cells are NaN
    pub table: Table,
    /// the resolved scene of the run
    pub scene: Scene,
    /// grain diameter d (m)
    pub d: f64,
    /// grain density rho_p (kg/m^3)
    pub rho_p: f64,
    /// fluid dynamic viscosity eta_f = rho_f nu_f (Pa s)
    pub eta_f: f64,
}

impl RunFields {
    /// Read `dir/profiles.csv` and `dir/scene.toml`. Errors name the folder or the file.
    pub fn read(dir: &Path) -> anyhow::Result<RunFields> {
        if !dir.is_dir() {
            bail!("{}: no such run output folder (give the folder `saltus run` wrote)", dir.display());
        }
        let profiles_path = dir.join(run_files::PROFILES);
        let scene_path = dir.join(run_files::SCENE);
        for f in [&profiles_path, &scene_path] {
            if !f.is_file() {
                bail!("{}: missing; a run's output folder holds profiles.csv and scene.toml", f.display());
            }
        }
        let table = run_files::profiles_table(dir)?;
        let scene = Scene::from_file(&scene_path).with_context(|| format!("{}: cannot load", scene_path.display()))?;
        RunFields::new(profiles_path, table, scene)
    }

    /// Fields of profiles `table` (named `profiles_path` in messages) of a run of `scene`,
    /// e.g. a run's [`saltus_solvers::RunReport`] held in memory, at full precision.
    pub fn new(profiles_path: PathBuf, table: Table, scene: Scene) -> anyhow::Result<RunFields> {
        let p = &scene.particles;
        let (d, rho_p) = (p.diameter, p.density);
        let eta_f = scene.fluid.density * scene.fluid.viscosity;
        let rows = table.rows();
        if let Some(name) = table.names.iter().zip(&table.columns).find(|(_, c)| c.len() != rows).map(|(n, _)| n) {
            bail!("{}: column `{name}` does not have the {rows} rows of the first", profiles_path.display());
        }
        let fields = RunFields { profiles_path, table, scene, d, rho_p, eta_f };
        fields.column("z", "every comparison")?;
        fields.column("phi", "every comparison")?;
        Ok(fields)
    }

    /// Column `name`, needed by `what`; an error names the file, the column and what the
    /// file has.
    pub fn column(&self, name: &str, what: &str) -> anyhow::Result<&[f64]> {
        self.table.get(name).ok_or_else(|| {
            anyhow!(
                "{}: missing column `{name}`, needed for {what} (found: {}); a DEM run writes the averaged granular \
                 fields only when they are switched on, see docs/diagnostics.md",
                self.profiles_path.display(),
                self.table.names.join(", ")
            )
        })
    }

    /// Column `name` if the file has it.
    pub fn optional(&self, name: &str) -> Option<&[f64]> {
        self.table.get(name)
    }

    /// The measured stress ratio mu = tau_p / p_p of every cell: the `mu_eff` column, or
    /// `tau_p / p_p` when the file has no `mu_eff`.
    pub fn friction(&self, what: &str) -> anyhow::Result<Vec<f64>> {
        if let Some(mu) = self.optional("mu_eff") {
            return Ok(mu.to_vec());
        }
        let tau = self.column("tau_p", what).context("neither `mu_eff` nor `tau_p`")?;
        let p = self.column("p_p", what)?;
        Ok(tau.iter().zip(p).map(|(t, p)| t / p).collect())
    }

    /// Local state of a cell of shear rate `gamma` under pressure `p`.
    pub fn state(&self, gamma: f64, p: f64) -> LocalState {
        LocalState {
            shear_rate: gamma,
            pressure: p,
            diameter: self.d,
            particle_density: self.rho_p,
            fluid_viscosity: self.eta_f,
        }
    }

    /// Number of cells.
    pub fn rows(&self) -> usize {
        self.table.rows()
    }
}
