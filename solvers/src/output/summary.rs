//! `summary.json`: the figures of a run, with its wall time by stage.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// `summary.json`.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Summary {
    /// scene name
    pub scene: String,
    /// solver
    pub solver: String,
    /// transport rate per unit width, integral of phi u_p dz (m^2/s); absent when the run
    /// measured none (a DEM run that ended before its first averaging sample, or without
    /// fluid)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs: Option<f64>,
    /// qs / sqrt((s - 1) g d^3); absent with qs or without a density contrast
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_star: Option<f64>,
    /// DEM runs: standard error of the time-averaged qs (m^2/s), Flyvbjerg-Petersen
    /// blocking of the qs samples of the averaging window with the block length chosen by
    /// Jonsson's test ([`crate::lagrangian::stats::blocking::Blocking`]); absent where it cannot be
    /// estimated (too few samples, or blocks that stay correlated: the paragraph says
    /// which)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_stderr: Option<f64>,
    /// DEM runs: standard error of qs_star, qs_stderr on the same scale
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_star_stderr: Option<f64>,
    /// largest fluid shear stress (viscous + turbulent) over (rho_p - rho_f) g d; absent
    /// when not measured
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shields: Option<f64>,
    /// rho_f g sin(alpha) h_w / ((rho_p - rho_f) g cos(alpha) d) with the scene's water depth
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shields_nominal: Option<f64>,
    /// level below which 1 % of qs flows (m): the bed surface; absent without transport
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bed_height: Option<f64>,
    /// distance between the levels below which 1 % and 99 % of qs flow (m); absent
    /// without transport
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transport_layer_thickness: Option<f64>,
    /// total height of the cells whose local flux phi u_p exceeds 0.05 sqrt((s - 1) g d)
    /// (m): the transport layer of Cheng et al. section 4.2 (their delta_t, delta_b);
    /// absent without a density contrast or where no cell exceeds it
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flux_layer_thickness: Option<f64>,
    /// steady-state criterion met
    pub steady: bool,
    /// steady, end_time, max_steps, interrupted or unstable
    pub ending: String,
    /// simulated time (s)
    pub sim_time_s: f64,
    /// accepted steps (of the flow: the DEM's deposition is in `total_steps`)
    pub steps: usize,
    /// DEM runs: steps of the whole run, the deposition's included
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_steps: Option<usize>,
    /// DEM runs: averaging samples (one per fluid update from `stats_start` on), the
    /// samples of the time averages and of qs_stderr
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// rejected (retried) steps; absent for solvers without step rejection (the DEM)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rejected_steps: Option<usize>,
    /// wall-clock time of the solve (s)
    pub wall_time_s: f64,
    /// CPU time of the solve in this process (s): the calling thread's and the solver's
    /// own worker threads'; absent where the system does not tell it or where the DEM
    /// worked on a shared pool (`solver.lagrangian.threads = 0` inside `compare` or `sweep`)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_time_s: Option<f64>,
    /// relative change of the sediment mass over the run; absent where the solver does not
    /// measure it (the DEM conserves its particles by construction)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_error: Option<f64>,
    /// last steady residual in the solver's measure (see [`crate::run::Progress`]); absent
    /// before the solver has one
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    /// number of cells
    pub cells: usize,
    /// why the run stopped early, if it did
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Lagrangian runs: number of mobile particles
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particles: Option<usize>,
    /// Lagrangian runs: mobile particle-steps per wall-clock second of the flow phase
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particle_steps_per_s: Option<f64>,
    /// Lagrangian runs: Shields number from the largest turbulent (Reynolds) shear stress,
    /// Maurin et al. 2015's theta*
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shields_turbulent: Option<f64>,
    /// DEM runs without fluid: granular temperature of the mobile particles at the end
    /// (m^2/s^2), the last value of `theta_g` in `timeseries.csv`
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub granular_temperature: Option<f64>,
    /// homogeneous cooling scenes: Haff's cooling time of the kinetic theory (s), from the
    /// restitution, the packing and the initial temperature
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub haff_tau_s: Option<f64>,
    /// homogeneous cooling scenes: cooling time fitted to the temperature history (s)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub haff_tau_fit_s: Option<f64>,
    /// homogeneous cooling scenes: Haff's temperature T0 / (1 + t/tau)^2 at the end
    /// (m^2/s^2)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub haff_granular_temperature: Option<f64>,
    /// homogeneous cooling scenes: largest relative deviation |T / T_Haff - 1| over the
    /// temperature samples (one per fluid period)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub haff_max_deviation: Option<f64>,
    /// runs with an active fluctuation closure: Rouse number of the phi profile fitted as
    /// Cheng et al. eqs 38-39 over 0.1 h <= z - z_b <= 0.5 h ([`crate::measures::rouse`]), with z_b
    /// the initial bed height and h the water depth of the scene; absent where undefined
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rouse_number: Option<f64>,
    /// runs under a periodic forcing with phase averages (`output.phases`): the net
    /// transport per period, the mean over the averaged periods of the integral of qs over
    /// one period (m^2; `phases.json`); absent before a whole period is averaged
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net_transport: Option<f64>,
    /// its standard error over the averaged periods (m^2), with two periods or more
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net_transport_stderr: Option<f64>,
    /// DEM runs with a fluid: the start (s) of the averaging window MSER-5 finds in the
    /// run's own transport rate (`docs/lagrangian.md`); absent while it is still climbing
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window_start_s: Option<f64>,
    /// the transport rate over that window (m^2/s)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_window: Option<f64>,
    /// its standard error (m^2/s), blocks of batch means chosen from their correlation
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_window_stderr: Option<f64>,
    /// Geweke's z between the window's first 10 % and last 50 % (level within +-2)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_window_geweke_z: Option<f64>,
    /// the statistical inefficiency (twice the integrated correlation time, s of flow)
    /// that error is taken with: the window's own or, where larger, the developed state's
    /// a warm start came from
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qs_window_inefficiency_s: Option<f64>,
    /// DEM runs: neighbour-list builds of the whole run, the deposition's included (per
    /// step: over `total_steps`)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neighbour_builds: Option<usize>,
    /// wall time of the run in this process by stage ([`Timing`])
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timing: Option<Timing>,
}

/// The wall time of a run by stage, as written in `summary.json`: the solver's stages,
/// the driver's `output` (the observers: time series, snapshots, checkpoints, ParaView)
/// and `other` (the rest of the run's wall time: set-up, the progress display, the loop),
/// which add up to `wall`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timing {
    /// wall time of the run in this process (s)
    pub wall: f64,
    /// seconds per stage
    pub stages: BTreeMap<String, f64>,
}

impl Timing {
    /// The timing of a run of `wall` seconds whose solver counted `solver` and whose
    /// observers took `output` seconds; `other` is what remains.
    pub fn new(wall: f64, solver: impl Iterator<Item = (&'static str, f64)>, output: f64) -> Self {
        let mut stages: BTreeMap<String, f64> = solver.map(|(k, v)| (k.to_string(), v)).collect();
        stages.insert("output".into(), output);
        let counted: f64 = stages.values().sum();
        stages.insert("other".into(), (wall - counted).max(0.0));
        Self { wall, stages }
    }

    /// One line: the stages by decreasing time with their share of the wall time.
    pub fn line(&self) -> String {
        let mut v: Vec<(&String, &f64)> = self.stages.iter().filter(|(_, s)| **s > 0.0).collect();
        v.sort_by(|a, b| b.1.total_cmp(a.1));
        let total = self.wall.max(f64::MIN_POSITIVE);
        let parts: Vec<String> =
            v.iter().map(|(k, s)| format!("{k} {:.3} s ({:.1} %)", s, 100.0 * **s / total)).collect();
        format!("wall time {:.3} s: {}", self.wall, parts.join(", "))
    }
}

/// `x` when it is a finite number: a summary figure that is not one is absent.
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}
