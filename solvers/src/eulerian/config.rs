//! The `[domain]` and `[solver]` tables of an Eulerian scene, typed and checked.

use std::path::Path;

use saltus_core::scene::{check, domain_and_solver, Scene};
use saltus_core::{Error, ParamRange};
use serde::{Deserialize, Serialize};

/// Top boundary of the column.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Top {
    /// zero shear stress (open channel)
    #[default]
    FreeSurface,
    /// moving lid at `lid_velocity` (Couette)
    Lid,
    /// symmetry plane (channel centreline)
    Symmetry,
}

/// `[domain]`: the column. Heights in metres.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Domain {
    /// thickness of the initial sediment bed at rest (m); 0 for clear fluid
    #[serde(default)]
    pub bed_height: f64,
    /// volume fraction of the initial bed; default 0.61 (Chassagne 2023 set-up), or
    /// 0.95 of the closure's maximum packing when that is lower
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bed_phi: Option<f64>,
    /// uniform volume fraction of a suspension above the bed at start (hindered settling)
    #[serde(default)]
    pub suspension_phi: f64,
    /// clear fluid above the initial bed (m); the column height is bed_height + water_depth
    pub water_depth: f64,
    /// number of cells
    pub cells: usize,
    /// ratio of the heights of successive cells from the bottom, dz_(i+1) = r dz_i: 1 is a
    /// uniform grid, r > 1 refines towards the bottom wall (a smooth-wall channel needs the
    /// near-wall 1/z^2 of omega resolved, see docs/benchmarks.md); in [1, 1.2], where the
    /// linear face interpolation of the solver keeps its second-order error small
    #[serde(default = "unit_stretching")]
    pub stretching: f64,
    /// top boundary
    #[serde(default)]
    pub top: Top,
    /// lid velocity (m/s) when `top = "lid"`
    #[serde(default)]
    pub lid_velocity: f64,
}

fn unit_stretching() -> f64 {
    1.0
}

/// `[solver]` of `type = "eulerian"`: time stepping and numerics.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// solver name, `eulerian`
    #[serde(rename = "type")]
    pub kind: String,
    /// stop at this simulated time (s) if not steady before
    pub end_time: f64,
    /// steady when the largest relative rate of change of u_f, u_p, phi and T is below
    /// this (1/s) for `steady_steps` consecutive steps
    pub steady_tolerance: f64,
    /// consecutive steps under the tolerance needed to call the run steady
    pub steady_steps: usize,
    /// first time step (s)
    pub dt_initial: f64,
    /// largest time step (s)
    pub dt_max: f64,
    /// smallest time step (s): below it the run stops as unstable
    pub dt_min: f64,
    /// largest change of phi in one cell per step; a larger one rejects the step
    pub max_phi_change: f64,
    /// cap on the number of accepted steps
    pub max_steps: usize,
    /// shear rate (1/s) regularising the rate-independent (Coulomb) stresses:
    /// tau = mu p gamma_dot / sqrt(gamma_dot^2 + r^2)
    pub shear_rate_regularisation: f64,
    /// under-relaxation of the eddy viscosity between steps, in (0, 1]
    pub eddy_relaxation: f64,
    /// elastic (enduring-contact) pressure P0 of Johnson & Jackson for local rheologies
    /// (Pa); kinetic closures carry their own
    pub elastic_p0: f64,
    /// random loose packing where the elastic pressure of local rheologies starts
    pub elastic_phi_rlp: f64,
    /// initial granular temperature (m^2/s^2) in the bed, a seed for the kinetic equation
    pub initial_temperature: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            kind: "eulerian".into(),
            end_time: 300.0,
            steady_tolerance: 1e-6,
            steady_steps: 20,
            dt_initial: 1e-4,
            dt_max: 1.0,
            dt_min: 1e-9,
            max_phi_change: 0.02,
            max_steps: 2_000_000,
            shear_rate_regularisation: 1e-4,
            eddy_relaxation: 0.5,
            elastic_p0: 0.05,
            elastic_phi_rlp: 0.57,
            initial_temperature: 1e-6,
        }
    }
}

/// Checked configuration of one Eulerian run.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// the column
    pub domain: Domain,
    /// the numerics
    pub settings: Settings,
}

impl Config {
    /// Read `[domain]` and `[solver]` of `scene`, with errors that name the file and key.
    pub fn from_scene(scene: &Scene) -> Result<Config, Error> {
        let file = scene.path.as_path();
        let (domain, settings): (Domain, Settings) =
            domain_and_solver(scene, "an Eulerian scene needs water_depth and cells")?;
        let cfg = Config { domain, settings };
        cfg.check(file)?;
        Ok(cfg)
    }

    fn check(&self, file: &Path) -> Result<(), Error> {
        let d = &self.domain;
        check(file, "domain.bed_height", d.bed_height, ParamRange::non_negative())?;
        check(file, "domain.water_depth", d.water_depth, ParamRange::non_negative())?;
        if d.bed_height + d.water_depth <= 0.0 {
            return Err(Error::Key {
                file: file.into(),
                key: "domain.water_depth".into(),
                message: "the column height bed_height + water_depth must be > 0".into(),
            });
        }
        if let Some(p) = d.bed_phi {
            check(file, "domain.bed_phi", p, ParamRange::open(0.0, 1.0))?;
        }
        check(file, "domain.suspension_phi", d.suspension_phi, ParamRange::closed_open(0.0, 1.0))?;
        check(file, "domain.cells", d.cells as f64, ParamRange::closed(4.0, 100_000.0))?;
        check(file, "domain.lid_velocity", d.lid_velocity, ParamRange::any())?;
        check(file, "domain.stretching", d.stretching, ParamRange::closed(1.0, 1.2))?;
        let s = &self.settings;
        check(file, "solver.end_time", s.end_time, ParamRange::positive())?;
        check(file, "solver.steady_tolerance", s.steady_tolerance, ParamRange::non_negative())?;
        check(file, "solver.steady_steps", s.steady_steps as f64, ParamRange::closed(1.0, 1e9))?;
        check(file, "solver.dt_initial", s.dt_initial, ParamRange::positive())?;
        check(file, "solver.dt_max", s.dt_max, ParamRange::positive())?;
        check(file, "solver.dt_min", s.dt_min, ParamRange::open(0.0, s.dt_initial.min(s.dt_max)))?;
        check(file, "solver.max_phi_change", s.max_phi_change, ParamRange::open_closed(0.0, 0.5))?;
        check(file, "solver.max_steps", s.max_steps as f64, ParamRange::closed(1.0, 1e12))?;
        check(file, "solver.shear_rate_regularisation", s.shear_rate_regularisation, ParamRange::positive())?;
        check(file, "solver.eddy_relaxation", s.eddy_relaxation, ParamRange::open_closed(0.0, 1.0))?;
        check(file, "solver.elastic_p0", s.elastic_p0, ParamRange::positive())?;
        check(file, "solver.elastic_phi_rlp", s.elastic_phi_rlp, ParamRange::open(0.0, 1.0))?;
        check(file, "solver.initial_temperature", s.initial_temperature, ParamRange::positive())?;
        Ok(())
    }
}
