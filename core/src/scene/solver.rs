//! `[solver]`: which solver runs (`type`) and the numerics of both, `[solver.eulerian]`
//! and `[solver.lagrangian]`. Both sub-tables are always typed and checked, whichever
//! is active, so that one scene carries both and `--set solver.type=...` switches.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{check, MAX_TIME};
use crate::error::Result;
use crate::param::ParamRange;

pub use super::lagrangian::{Bottom, FluidMode, Initial, LagrangianSettings, ParticleSpec, Surface};

/// The solvers.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SolverKind {
    /// two-fluid column (Chassagne et al. 2023)
    #[default]
    Eulerian,
    /// soft-sphere DEM coupled to the fluid column (Maurin et al. 2015)
    Lagrangian,
}

impl SolverKind {
    /// The name used in scenes and summaries.
    pub fn name(self) -> &'static str {
        match self {
            SolverKind::Eulerian => "eulerian",
            SolverKind::Lagrangian => "lagrangian",
        }
    }
}

/// `[solver]`. A scene without it runs the Eulerian solver with default numerics.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct Solver {
    /// the solver that runs
    #[serde(rename = "type")]
    pub kind: SolverKind,
    /// numerics of the Eulerian solver
    pub eulerian: EulerianSettings,
    /// geometry and numerics of the DEM
    pub lagrangian: LagrangianSettings,
}

/// `[solver.eulerian]`: time stepping and numerics.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct EulerianSettings {
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
    /// relative change of the fields per step (the steady residual times the step) that
    /// the growth of a steady march's time step aims at; the steady state does not
    /// depend on it, the number of steps to it does
    pub target_field_change: f64,
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
    /// random loose packing where the elastic pressure of local rheologies starts; default
    /// [`default_elastic_phi_rlp`] of the granular closure's packing
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elastic_phi_rlp: Option<f64>,
    /// initial granular temperature (m^2/s^2) in the bed, a seed for the kinetic equation
    pub initial_temperature: f64,
    /// how time is stepped ([`TimeStepping`])
    pub time_stepping: TimeStepping,
    /// closure tables that replace the scene's `[closures.<family>]`, family by family,
    /// when this solver runs (the Eulerian face of a closure whose coupling differs
    /// between the solvers)
    #[serde(skip_serializing_if = "toml::Table::is_empty")]
    pub closures: toml::Table,
}

/// `solver.eulerian.time_stepping`: march to a steady state, or follow the flow in time.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum TimeStepping {
    /// backward Euler with a time step that grows while the fields change little, ending
    /// at the steady state (`steady_tolerance`, `steady_steps`) or the end time
    #[default]
    Steady,
    /// every transported field (momentum of both phases, phi, granular temperature, k and
    /// omega) by the variable-step second-order backward differentiation formula (BDF2),
    /// the coefficients at the extrapolation of the last two states, at a step of at most
    /// `dt_max`, limited by the phi changes only (shorter after a rejection, or to land on
    /// the end time), no steady ending: the run follows a time-dependent forcing to the end
    /// time.
    Accurate,
}

impl Default for EulerianSettings {
    fn default() -> Self {
        Self {
            end_time: 300.0,
            steady_tolerance: 1e-6,
            steady_steps: 20,
            dt_initial: 1e-4,
            dt_max: 1.0,
            dt_min: 1e-9,
            max_phi_change: 0.02,
            target_field_change: 0.5,
            max_steps: 2_000_000,
            shear_rate_regularisation: 1e-4,
            eddy_relaxation: 0.5,
            elastic_p0: 0.05,
            elastic_phi_rlp: None,
            initial_temperature: 1e-6,
            time_stepping: TimeStepping::Steady,
            closures: toml::Table::new(),
        }
    }
}

impl EulerianSettings {
    pub(super) fn check(&self, f: &Path) -> Result<()> {
        let p = |k: &str| format!("solver.eulerian.{k}");
        check(f, &p("end_time"), self.end_time, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("steady_tolerance"), self.steady_tolerance, ParamRange::closed(0.0, 1e6))?;
        check(f, &p("steady_steps"), self.steady_steps as f64, ParamRange::closed(1.0, 1e9))?;
        check(f, &p("dt_initial"), self.dt_initial, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("dt_max"), self.dt_max, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("dt_min"), self.dt_min, ParamRange::open(0.0, self.dt_initial.min(self.dt_max)))?;
        check(f, &p("max_phi_change"), self.max_phi_change, ParamRange::open_closed(0.0, 0.5))?;
        check(f, &p("target_field_change"), self.target_field_change, ParamRange::open_closed(0.0, 10.0))?;
        check(f, &p("max_steps"), self.max_steps as f64, ParamRange::closed(1.0, 1e12))?;
        check(f, &p("shear_rate_regularisation"), self.shear_rate_regularisation, ParamRange::open_closed(0.0, 1e6))?;
        check(f, &p("eddy_relaxation"), self.eddy_relaxation, ParamRange::open_closed(0.0, 1.0))?;
        check(f, &p("elastic_p0"), self.elastic_p0, ParamRange::open_closed(0.0, 1e9))?;
        if let Some(rlp) = self.elastic_phi_rlp {
            check(f, &p("elastic_phi_rlp"), rlp, ParamRange::open(0.0, 1.0))?;
        }
        check(f, &p("initial_temperature"), self.initial_temperature, ParamRange::open_closed(0.0, 1e6))
    }
}

/// Random loose packing of the elastic pressure of the local rheologies, reference value
/// (Chauchat 2018 with phi_c = 0.61).
pub const ELASTIC_PHI_RLP: f64 = 0.57;

/// Default `solver.eulerian.elastic_phi_rlp` for a granular closure of packing `phi_max`
/// at zero shear: 0.57, or the same fraction 0.57 / 0.61 of the packing when the packing
/// is below 0.61, so that the default stays below the packing (0.57 is refused for any
/// phi_c <= 0.57) and is unchanged for the usual phi_c >= 0.61.
pub fn default_elastic_phi_rlp(phi_max: f64) -> f64 {
    ELASTIC_PHI_RLP.min(phi_max * ELASTIC_PHI_RLP / 0.61)
}
