//! What a run leaves behind: cell profiles, a summary, the resolved scene and a manifest.
//! One contract for both solvers.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_core::Error;
use serde::{Deserialize, Serialize};

/// Named columns of equal length, written as `profiles.csv`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profiles {
    /// (name, values) in column order; the first is `z`
    pub columns: Vec<(String, Vec<f64>)>,
}

impl Profiles {
    /// Add a column.
    pub fn push(&mut self, name: &str, values: Vec<f64>) {
        self.columns.push((name.to_string(), values));
    }
    /// Column by name.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_slice())
    }
    /// CSV text with a header line. A value that is not a finite number (undefined there,
    /// e.g. the inertial number where the grains carry no pressure) is an empty cell:
    /// no `NaN` or `inf` is ever written.
    pub fn to_csv(&self) -> String {
        let mut s = self.columns.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(",");
        s.push('\n');
        let rows = self.columns.first().map_or(0, |c| c.1.len());
        for r in 0..rows {
            for (k, (_, v)) in self.columns.iter().enumerate() {
                if k > 0 {
                    s.push(',');
                }
                if v[r].is_finite() {
                    let _ = write!(s, "{:.10e}", v[r]);
                }
            }
            s.push('\n');
        }
        s
    }
}

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
    /// Cheng et al. eqs 38-39 over 0.1 h <= z - z_b <= 0.5 h ([`crate::rouse`]), with z_b
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

/// `manifest.json`: enough to reproduce the run.
#[derive(Clone, Debug, Serialize)]
pub struct Manifest<'a> {
    /// program version
    pub version: &'static str,
    /// git revision of the build, when built from a checkout
    pub git_revision: &'static str,
    /// scene file as given
    pub scene_file: String,
    /// scene seed
    pub seed: u64,
    /// closure model per family
    pub closures: Vec<(&'static str, &'a str)>,
    /// output files
    pub files: Vec<&'static str>,
    /// wall-clock time of the solve (s)
    pub wall_time_s: f64,
}

/// Git revision baked in at build time, or `unknown`.
pub const GIT_REVISION: &str = match option_env!("SALTUS_GIT_REVISION") {
    Some(r) => r,
    None => "unknown",
};

fn io(file: PathBuf) -> impl FnOnce(std::io::Error) -> Error {
    move |source| Error::Io { file, source }
}

/// The files [`write_run`] writes, with the time series, in the order of the manifest.
pub const RUN_FILES: [&str; 5] = ["profiles.csv", "summary.json", "scene.toml", "manifest.json", "timeseries.csv"];

/// File name of the checkpoint in its folder ([`crate::run::checkpoint`]).
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// Refuse an output folder `dir` that is an empty path, or where a file the run writes
/// ([`RUN_FILES`], the checkpoint) is one of the run's inputs (the scene file, a reference
/// file). The resolved scene may be rewritten over the scene file it was resolved from
/// when the text is the same (a run of a folder's own `scene.toml` into that folder,
/// `--restart` included): nothing is lost then.
pub fn check_out(dir: &Path, scene: &Scene) -> Result<(), Error> {
    let file = scene.path.display();
    if dir.as_os_str().is_empty() {
        return Err(Error::Invalid(format!(
            "{file}: the output folder is an empty path; give a folder (--out or output.dir), or leave output.dir out for out/<meta.name>"
        )));
    }
    let same = |a: &Path, b: &Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y);
    let inputs = std::iter::once(("the scene file", scene.path.clone()))
        .chain(scene.reference.iter().map(|r| ("the reference file", PathBuf::from(&r.file))));
    for (what, input) in inputs {
        for name in RUN_FILES.iter().chain([&CHECKPOINT_FILE]) {
            let written = dir.join(name);
            if !same(&written, &input) {
                continue;
            }
            if *name == "scene.toml" && what == "the scene file" {
                let unchanged = std::fs::read_to_string(&input).ok() == Some(scene.to_toml()?);
                if unchanged {
                    continue;
                }
            }
            return Err(Error::Invalid(format!(
                "{file}: the run would write {} over {what} {}; choose another output folder (--out or output.dir)",
                written.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

/// Write `profiles.csv`, `summary.json`, `scene.toml` (resolved) and `manifest.json` into
/// `dir` (created if needed).
pub fn write_run(dir: &Path, scene: &Scene, profiles: &Profiles, summary: &Summary) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(io(dir.to_path_buf()))?;
    let put = |name: &str, text: String| -> Result<(), Error> {
        let f = dir.join(name);
        std::fs::write(&f, text).map_err(io(f))
    };
    put("profiles.csv", profiles.to_csv())?;
    let json = serde_json::to_string_pretty(summary).map_err(|e| Error::Invalid(format!("summary: {e}")))?;
    put("summary.json", json + "\n")?;
    put("scene.toml", scene.to_toml()?)?;
    let cl = &scene.closures;
    let name = |m: Option<&dyn saltus_core::Describe>| m.map_or("none", |m| m.name());
    let manifest = Manifest {
        version: env!("CARGO_PKG_VERSION"),
        git_revision: GIT_REVISION,
        scene_file: scene.path.display().to_string(),
        seed: scene.seed,
        closures: vec![
            ("drag", name(cl.drag.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("hindrance", name(cl.hindrance.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("viscosity", name(cl.viscosity.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("granular", name(cl.granular.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("turbulence", name(cl.turbulence.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("fluctuation", name(cl.fluctuation.as_deref().map(|m| m as &dyn saltus_core::Describe))),
        ],
        files: RUN_FILES.to_vec(),
        wall_time_s: summary.wall_time_s,
    };
    let json = serde_json::to_string_pretty(&manifest).map_err(|e| Error::Invalid(format!("manifest: {e}")))?;
    put("manifest.json", json + "\n")
}

/// Scales that turn a run's transport and stresses into the dimensionless numbers of the
/// summary, the same for every solver: qs* = qs / sqrt((s-1) g d^3), Shields = tau /
/// ((rho_p - rho_f) g d), nominal Shields = rho_f g sin h_w / ((rho_p - rho_f) g cos d).
#[derive(Clone, Copy, Debug)]
pub struct TransportScales {
    /// sqrt(|s - 1| g d^3) (m^2/s)
    pub qs: f64,
    /// |rho_p - rho_f| g d (Pa)
    pub stress: f64,
    /// Shields number of the driving over the water depth, when the slope drives the flow
    pub shields_nominal: Option<f64>,
}

impl TransportScales {
    /// Scales of `scene` with particles of density `rho_p`, diameter `d` under a water
    /// depth `water_depth`.
    pub fn new(scene: &saltus_core::scene::Scene, rho_p: f64, d: f64, water_depth: f64) -> Self {
        let g = scene.physics.gravity;
        let rho_f = scene.fluid.density;
        let sm1 = rho_p / rho_f - 1.0;
        let stress = (rho_p - rho_f).abs() * g * d;
        let slope = scene.physics.slope;
        let cos = (1.0 - slope * slope).max(0.0).sqrt();
        // undefined (absent) without a stress scale: no gravity or no density contrast
        let shields_nominal = (slope > 0.0 && water_depth > 0.0 && sm1 > 0.0)
            .then(|| rho_f * g * slope * water_depth / (stress * cos))
            .and_then(finite);
        Self { qs: (sm1.abs() * g * d * d * d).sqrt(), stress, shields_nominal }
    }

    /// sqrt(|s - 1| g d) (m/s), the velocity scale of a local flux phi u_p: qs over d.
    pub fn flux_velocity(&self, d: f64) -> f64 {
        self.qs / d
    }

    /// qs* of a transport rate qs (m^2/s); NaN without a scale.
    pub fn qs_star(&self, qs: f64) -> f64 {
        if self.qs > 0.0 {
            qs / self.qs
        } else {
            f64::NAN
        }
    }

    /// Shields number of a shear stress (Pa); NaN without a scale.
    pub fn shields(&self, tau: f64) -> f64 {
        if self.stress > 0.0 {
            tau / self.stress
        } else {
            f64::NAN
        }
    }
}

/// `x` when it is a finite number: a summary figure that is not one is absent.
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Levels (m) below which the fractions `lo` and `hi` of the integral of `q dz` lie,
/// interpolated linearly inside cells.
pub fn flux_levels(faces: &[f64], q: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    flux_levels_by(q.len().min(faces.len().saturating_sub(1)), |i| faces[i], |i| q[i], lo, hi)
}

/// Threshold of the local flux phi u_p over sqrt((s - 1) g d) above which a cell is in
/// the transport layer of Cheng et al. (section 4.2).
pub const FLUX_LAYER_THRESHOLD: f64 = 0.05;

/// Total height (m) of the cells between `faces` whose flux density `q` (m/s) exceeds
/// [`FLUX_LAYER_THRESHOLD`] times `scale` = sqrt((s - 1) g d) (m/s); NaN without a scale
/// or where no cell exceeds it. Summed cell by cell rather than taken between the lowest
/// and highest such cell, so that one noisy cell of a DEM profile above the layer does not
/// count the clear water below it.
pub fn flux_layer_thickness(faces: &[f64], q: &[f64], scale: f64) -> f64 {
    if !(scale > 0.0 && scale.is_finite()) {
        return f64::NAN;
    }
    let limit = FLUX_LAYER_THRESHOLD * scale;
    let h: f64 = q.iter().zip(faces.windows(2)).filter(|(q, _)| **q > limit).map(|(_, f)| f[1] - f[0]).sum();
    if h > 0.0 {
        h
    } else {
        f64::NAN
    }
}

/// [`flux_levels`] over `n` cells with face `i` at `face(i)` and the flux density of cell
/// `i` `q(i)`: for fields that are not stored as one slice (a product of two, a uniform
/// grid), without allocating.
pub fn flux_levels_by(n: usize, face: impl Fn(usize) -> f64, q: impl Fn(usize) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    let total: f64 = (0..n).map(|i| q(i) * (face(i + 1) - face(i))).sum();
    if total.abs() <= 0.0 || !total.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let level = |frac: f64| {
        let target = frac * total;
        let mut acc = 0.0;
        for i in 0..n {
            let (a, b) = (face(i), face(i + 1));
            let add = q(i) * (b - a);
            if (acc + add) / total >= frac && add != 0.0 {
                return a + (target - acc) / add * (b - a);
            }
            acc += add;
        }
        face(n)
    };
    (level(lo), level(hi))
}

/// d f / dz of a cell profile at its centres `z` (increasing): the central difference
/// (f[i+1] - f[i-1]) / (z[i+1] - z[i-1]) inside, one-sided at the two ends (exact for a
/// linear profile on any grid); zeros with fewer than two cells. The one gradient of
/// written profiles, so that a run's `heat_flux` and `saltus diagnose`'s -kappa dT/dz
/// difference the same way.
pub fn profile_gradient(z: &[f64], f: &[f64]) -> Vec<f64> {
    let n = z.len().min(f.len());
    if n < 2 {
        return vec![0.0; n];
    }
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (f[b] - f[a]) / (z[b] - z[a])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flux_levels_of_a_uniform_layer() {
        let faces: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let q = [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let (a, b) = flux_levels(&faces, &q, 0.01, 0.99);
        assert!((a - 2.04).abs() < 1e-12 && (b - 5.96).abs() < 1e-12, "{a} {b}");
    }

    /// Cheng's transport layer of a flux profile q = phi u_p: the cells above 0.05
    /// sqrt((s - 1) g d), on a stretched grid, whatever the flux does in the others.
    #[test]
    fn the_flux_layer_counts_the_cells_above_the_threshold() {
        let faces = [0.0, 1.0, 1.5, 2.5, 4.0, 4.5, 6.0];
        let scale = 2.0; // the threshold is then 0.1
        let q = [0.01, 0.2, 0.5, 0.099, 0.3, 0.05];
        let h = flux_layer_thickness(&faces, &q, scale);
        assert!((h - (0.5 + 1.0 + 0.5)).abs() < 1e-12, "{h}");
        assert!(flux_layer_thickness(&faces, &[0.0; 6], scale).is_nan());
        for bad in [0.0, f64::NAN, f64::INFINITY, -1.0] {
            assert!(flux_layer_thickness(&faces, &q, bad).is_nan());
        }
    }

    #[test]
    fn gradient_of_a_linear_profile_is_exact() {
        let z = [0.1, 0.3, 0.4, 0.8];
        let f: Vec<f64> = z.iter().map(|z| 2.0 - 3.0 * z).collect();
        for g in profile_gradient(&z, &f) {
            assert!((g + 3.0).abs() < 1e-12, "{g}");
        }
        assert_eq!(profile_gradient(&[1.0], &[2.0]), vec![0.0]);
    }

    #[test]
    fn csv_has_header_and_rows() {
        let mut p = Profiles::default();
        p.push("z", vec![0.5, 1.5]);
        p.push("phi", vec![0.6, 0.0]);
        p.push("inertial_number", vec![0.1, f64::INFINITY]);
        let csv = p.to_csv();
        assert!(csv.starts_with("z,phi,inertial_number\n"));
        assert_eq!(csv.lines().count(), 3);
        assert!(csv.ends_with(",0.0000000000e0,\n"), "undefined is an empty cell: {csv}");
    }
}
