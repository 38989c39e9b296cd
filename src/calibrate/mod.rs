//! `saltus calibrate`: closure constants fitted jointly against a reference (several seeds
//! of a DEM run, any run folders, or the base scene's data), with their uncertainty.
//!
//! ```toml
//! base = "case14.toml"              # the Eulerian scene whose constants are fitted
//! set = []                          # overrides of every run
//! [[parameter]]
//! key = "closures.granular.g0.a0"   # any numeric key of a closure table
//! bounds = [0.0, 10.0]
//! # start = 0.58                    # default: the base scene's value
//! # prior = { mean = 0.58, sd = 0.3 }
//! [reference]
//! runs = ["dem_seed1", "dem_seed2"] # run folders (profiles.csv, summary.json), one per seed
//! # data = true                     # or the base scene's [[reference]] data, with scatter
//! smooth = 1.0                      # Fry et al. 2024 eq 11's Gaussian of h_g = 1 d (runs)
//! align = true                      # each profile from its bed surface (runs)
//! # scatter = { phi = 0.02 }        # a term's scatter where the reference cannot give it
//! # correlation_length = 1.0        # grain diameters per independent value of a profile
//! [misfit]
//! terms = ["phi", "u_p", "qs_star"]
//! # weights = { qs_star = 1.0 }
//! [optimiser]
//! # max_evaluations = 400, tolerance = 1e-6, step = 1e-3, profile_points = 3, profile_span = 3
//! ```
//!
//! **The misfit.** Each term t is compared with the reference's scatter s_t (the standard
//! deviation of one seed about the seeds' mean, [`mod@reference`]): a profile term over the
//! reference's moving layer by its RMS difference, rho_t = RMS / s_t; qs* by
//! rho = |qs* - qs*_ref| / s. The minimised sum is the chi^2 of the statistical model in
//! which the reference (a mean of N seeds) scatters about the model: chi^2 = sum_t w_t
//! c_t rho_t^2, with c_t = N n_t for a profile term (n_t independent values: the layer's
//! thickness over the correlation length, one grain diameter by default, the Gaussian's
//! width when larger), c = N for qs*, weights w_t (1 by default) and one (p - mean)/sd
//! per prior. rho_t <= 1 means the model is as close to the mean as one seed is.
//!
//! **Uncertainty.** The covariance of the constants is the Laplace approximation at the
//! optimum, C = (J^T J)^-1 with J the Jacobian of the chi^2 residuals (unit weights):
//! `stderr_statistical`, what the reference's scatter alone allows. When the model cannot
//! reach the reference (chi^2_min > dof, the number of independent values less the
//! constants), the errors are scaled by sqrt(chi^2_min / dof) (`stderr`), as a fit with a
//! misfit larger than its noise is (Press et al., Numerical Recipes, 15.6). The profile
//! likelihood of each constant is chi^2 with that constant held at points about the
//! optimum and every other one refitted; where chi^2 is quadratic it is
//! ((p - p_opt) / stderr_statistical)^2.

mod bounds;
mod figures;
mod model;
mod optimise;
mod output;
pub mod reference;
pub mod spec;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use nalgebra::DMatrix;
use rayon::prelude::*;
use saltus_solvers::RunReport;

pub use model::{term_names, Evaluation, Problem};
pub use spec::{load, Calibration, Parameter, TERMS};

/// File names written in the output folder.
pub const CALIBRATED: &str = "calibrated.toml";
/// See [`CALIBRATED`].
pub const TABLE: &str = "calibration.csv";
/// See [`CALIBRATED`].
pub const JSON: &str = "calibration.json";
/// See [`CALIBRATED`].
pub const PROFILES_FIGURE: &str = "calibration_profiles.png";
/// See [`CALIBRATED`].
pub const LIKELIHOOD_FIGURE: &str = "profile_likelihood.png";

/// One term's misfit at a point.
#[derive(Clone, Debug, serde::Serialize)]
pub struct TermMisfit {
    /// `phi`, `u_p` or `qs_star`
    pub term: String,
    /// RMS difference over the moving layer (profiles), or the signed difference (qs*)
    pub difference: f64,
    /// the reference's scatter of one seed
    pub scatter: f64,
    /// |difference| over the scatter
    pub ratio: f64,
}

/// One point of a profile likelihood.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ProfilePoint {
    /// the held value
    pub value: f64,
    /// chi^2 with the others refitted, less chi^2 at the optimum
    pub delta_chi2: f64,
    /// the refitted constants
    pub params: Vec<f64>,
}

/// A fitted constant.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Fitted {
    /// its key
    pub key: String,
    /// where the minimisation started
    pub start: f64,
    /// the optimum
    pub value: f64,
    /// standard error, scaled by the misfit the model cannot remove
    pub stderr: f64,
    /// standard error from the reference's scatter alone
    pub stderr_statistical: f64,
    /// below and above the optimum, the standard error of the profile likelihood: from
    /// its nearest point on each side, the parabola through the optimum and that point
    /// crosses delta chi^2 = 1 at this distance (NaN where the side has no point). Where it
    /// is smaller than `stderr_statistical`, chi^2 is curved more than J^T J says (the
    /// residuals' own curvature, which Gauss-Newton leaves out, weighs when chi^2_min is
    /// large) and the profile is the better error.
    pub stderr_profile: [f64; 2],
    /// bounds
    pub bounds: [f64; 2],
    /// whether the optimum sits within 1e-3 of the span of a bound
    pub at_bound: bool,
    /// its profile likelihood
    pub profile: Vec<ProfilePoint>,
}

/// Everything a calibration produced.
#[derive(Debug)]
pub struct CalibrationReport {
    /// output folder
    pub out: PathBuf,
    /// the fitted constants, in file order
    pub fitted: Vec<Fitted>,
    /// correlation matrix of the constants (row-major)
    pub correlation: Vec<Vec<f64>>,
    /// covariance matrix, scaled as `stderr`
    pub covariance: Vec<Vec<f64>>,
    /// terms at the start and at the optimum
    pub start_terms: Vec<TermMisfit>,
    /// see [`CalibrationReport::start_terms`]
    pub optimum_terms: Vec<TermMisfit>,
    /// chi^2 at the start and at the optimum
    pub chi2_start: f64,
    /// see [`CalibrationReport::chi2_start`]
    pub chi2: f64,
    /// independent values less the constants
    pub dof: f64,
    /// why the minimisation stopped
    pub reason: String,
    /// whether it converged
    pub converged: bool,
    /// model runs: minimisation, all in all
    pub evaluations_minimise: usize,
    /// see [`CalibrationReport::evaluations_minimise`]
    pub evaluations: usize,
    /// CPU time of every model run (s) and the wall time of the whole
    pub cpu_time_s: f64,
    /// see [`CalibrationReport::cpu_time_s`]
    pub wall_time_s: f64,
    /// files written
    pub files: Vec<PathBuf>,
    /// what did not fail the calibration but should be known
    pub warnings: Vec<String>,
}

/// Output folder when `--out` is not given: `out/<meta.name>`.
pub fn default_out(c: &Calibration) -> PathBuf {
    PathBuf::from("out").join(&c.meta.name)
}

fn terms(problem: &Problem, report: &RunReport, p: &[f64]) -> anyhow::Result<(Vec<TermMisfit>, f64)> {
    let fit = problem.fit(p, report).context("the run gives no profile to compare with the reference")?;
    let scatter: Vec<f64> = problem
        .reference
        .profiles
        .iter()
        .map(|t| t.scatter)
        .chain(problem.reference.rate.iter().map(|r| r.scatter))
        .collect();
    let t = term_names(&problem.cal)
        .into_iter()
        .enumerate()
        .map(|(k, term)| TermMisfit { term, difference: fit.rms[k], scatter: scatter[k], ratio: fit.ratios[k] })
        .collect();
    Ok((t, fit.chi2))
}

/// Inverse of a symmetric positive matrix, `None` when singular.
fn inverse(a: DMatrix<f64>) -> Option<DMatrix<f64>> {
    let inv = a.clone().cholesky().map(|c| c.inverse()).or_else(|| a.try_inverse())?;
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// Check `cal` as a run would (base scene, keys, bounds at both ends, reference) without
/// running the model; a line saying what it would fit.
pub fn check(cal: Calibration) -> anyhow::Result<String> {
    let file = cal.file.clone();
    let problem = Problem::new(cal)?;
    let r = &problem.reference;
    Ok(format!(
        "{}: {} free constants, {} reference terms over {} seed(s); ok",
        file.display(),
        problem.start.len(),
        r.profiles.len() + usize::from(r.rate.is_some()),
        r.seeds
    ))
}

/// Run the calibration `cal` into `out`: minimise, take the covariance at the optimum and
/// the profile likelihoods, write [`CALIBRATED`], [`TABLE`], [`JSON`] and the figures.
pub fn run(cal: Calibration, out: &Path) -> anyhow::Result<CalibrationReport> {
    let wall = Instant::now();
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let problem = Problem::new(cal)?;
    let m = problem.start.len();
    let all: Vec<usize> = (0..m).collect();
    let mut warnings = Vec::new();

    problem.anchor(&problem.start);
    let start_report = problem.run(&problem.start).context("the model at the start values")?;
    let (start_terms, chi2_start) = terms(&problem, &start_report, &problem.start)?;
    let budget = problem.cal.optimiser.max_evaluations;
    let mut from = problem.start.clone();
    let mut restarts = 0;
    let mut evaluations_minimise = 0;
    let (min, local) = loop {
        let min = optimise::minimise(&problem, &from, &all, budget, "minimise")
            .context("the model at the start values gives no misfit")?;
        evaluations_minimise += min.evaluations;
        let local = analyse(&problem, &min.params, &mut warnings)?;
        // a profile that refits below the optimum found a lower valley: start again there
        let lower = local
            .profiles
            .iter()
            .flatten()
            .filter(|p| p.delta_chi2 < -1e-3 * local.chi2.max(1.0))
            .min_by(|a, b| a.delta_chi2.total_cmp(&b.delta_chi2));
        match lower {
            Some(p) if restarts < MAX_RESTARTS => {
                warnings.push(format!(
                    "a profile likelihood refitted to chi2 {:.4} below the optimum's {:.4}: minimised again from there",
                    local.chi2 + p.delta_chi2,
                    local.chi2
                ));
                from = p.params.clone();
                restarts += 1;
            }
            _ => break (min, local),
        }
    };
    let optimum = min.params.clone();
    let Analysis { chi2, dof, inflation, stat, correlation, covariance, profiles } = local;
    let optimum_report = problem.run(&optimum).context("the model at the optimum")?;
    let (optimum_terms, _) = terms(&problem, &optimum_report, &optimum)?;

    let fitted: Vec<Fitted> = problem
        .cal
        .parameters
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let [lo, hi] = p.bounds;
            let near = 1e-3 * (hi - lo);
            Fitted {
                key: p.key.clone(),
                start: problem.start[k],
                value: optimum[k],
                stderr: stat[k] * inflation,
                stderr_statistical: stat[k],
                stderr_profile: profile_errors(optimum[k], &profiles[k]),
                bounds: p.bounds,
                at_bound: optimum[k] - lo < near || hi - optimum[k] < near,
                profile: profiles[k].clone(),
            }
        })
        .collect();
    for f in fitted.iter().filter(|f| f.at_bound) {
        warnings
            .push(format!("{} = {} sits at a bound of [{}, {}]: widen it", f.key, f.value, f.bounds[0], f.bounds[1]));
    }
    let log = problem.log.lock().map(|l| l.clone()).unwrap_or_default();
    let mut report = CalibrationReport {
        out: out.to_path_buf(),
        fitted,
        correlation,
        covariance,
        start_terms,
        optimum_terms,
        chi2_start,
        chi2,
        dof,
        reason: min.reason,
        converged: min.converged,
        evaluations_minimise,
        evaluations: log.len(),
        cpu_time_s: log.iter().map(|e| e.cpu_time_s).sum(),
        wall_time_s: 0.0,
        files: Vec::new(),
        warnings,
    };
    report.files.push(output::write_calibrated(&problem, &optimum, &report, out)?);
    report.files.push(output::write_table(&problem, &log, out)?);
    for png in [
        figures::profiles(&problem, &start_report, &optimum_report, &out.join(PROFILES_FIGURE)),
        figures::likelihood(&report, &out.join(LIKELIHOOD_FIGURE)),
    ] {
        match png {
            Ok(p) => report.files.push(p),
            Err(e) => report.warnings.push(format!("cannot draw: {e:#}")),
        }
    }
    report.wall_time_s = wall.elapsed().as_secs_f64();
    report.files.insert(2, output::write_json(&problem, &report, out)?);
    Ok(report)
}

/// The profile likelihood's standard error below and above `optimum` (see
/// [`Fitted::stderr_profile`]).
fn profile_errors(optimum: f64, profile: &[ProfilePoint]) -> [f64; 2] {
    let side = |below: bool| {
        profile
            .iter()
            .filter(|q| (q.value < optimum) == below && q.value != optimum && q.delta_chi2 > 0.0)
            .min_by(|a, b| (a.value - optimum).abs().total_cmp(&(b.value - optimum).abs()))
            .map_or(f64::NAN, |q| (q.value - optimum).abs() / q.delta_chi2.sqrt())
    };
    [side(true), side(false)]
}

impl CalibrationReport {
    /// A few lines for the terminal: each constant with its error, the misfit at the start
    /// and at the optimum against the scatter, the stopping reason and the cost.
    pub fn text(&self) -> String {
        let mut s = String::new();
        for f in &self.fitted {
            s.push_str(&format!(
                "{} = {:.6} +- {:.2e} (from the scatter alone +- {:.2e}; profile likelihood -{:.2e} +{:.2e}; start {})\n",
                f.key, f.value, f.stderr, f.stderr_statistical, f.stderr_profile[0], f.stderr_profile[1], f.start
            ));
        }
        let line =
            |t: &[TermMisfit]| t.iter().map(|m| format!("{} {:.3}x", m.term, m.ratio)).collect::<Vec<_>>().join(", ");
        s.push_str(&format!(
            "misfit / scatter: start {}; optimum {}\n",
            line(&self.start_terms),
            line(&self.optimum_terms)
        ));
        s.push_str(&format!(
            "chi2 {:.4} -> {:.4} ({:.1} dof); {}; {} model runs ({} to the optimum), {:.1} CPU-s, {:.1} s wall\n",
            self.chi2_start,
            self.chi2,
            self.dof,
            self.reason,
            self.evaluations,
            self.evaluations_minimise,
            self.cpu_time_s,
            self.wall_time_s
        ));
        s
    }
}

/// Most restarts of the minimisation from a lower point its profile likelihoods found.
const MAX_RESTARTS: usize = 2;

/// What the neighbourhood of an optimum says: its chi^2, the covariance and the profiles.
struct Analysis {
    chi2: f64,
    dof: f64,
    inflation: f64,
    stat: Vec<f64>,
    correlation: Vec<Vec<f64>>,
    covariance: Vec<Vec<f64>>,
    profiles: Vec<Vec<ProfilePoint>>,
}

/// The covariance at `optimum` (from its Jacobian, scaled by the reference's scatter and
/// inflated by chi^2/dof where that exceeds 1) and each constant's profile likelihood.
fn analyse(problem: &Problem, optimum: &[f64], warnings: &mut Vec<String>) -> anyhow::Result<Analysis> {
    let m = optimum.len();
    let optimum = &optimum.to_vec();
    let all: Vec<usize> = (0..m).collect();
    // the covariance and the profiles from the optimum's state
    problem.anchor(optimum);
    let (j, centre) = optimise::jacobian(problem, optimum, &all, "covariance")
        .context("the Jacobian at the optimum: a model run failed")?;
    let mut j_chi = j;
    for (i, s) in centre.chi_scale.iter().enumerate() {
        j_chi.row_mut(i).scale_mut(*s);
    }
    let chi2 = centre.chi2;
    let independent: f64 =
        problem.reference.profiles.iter().map(|t| t.independent * problem.reference.seeds as f64).sum::<f64>()
            + problem.reference.rate.map_or(0.0, |_| problem.reference.seeds as f64)
            + problem.cal.parameters.iter().filter(|p| p.prior.is_some()).count() as f64;
    let dof = (independent - m as f64).max(1.0);
    let inflation = (chi2 / dof).max(1.0).sqrt();
    let cov = inverse(j_chi.transpose() * &j_chi);
    if cov.is_none() {
        warnings.push(
            "the constants are not identifiable at the optimum (J^T J singular): no covariance; see the profile likelihoods"
                .into(),
        );
    }
    let stat: Vec<f64> = (0..m).map(|k| cov.as_ref().map_or(f64::NAN, |c| c[(k, k)].max(0.0).sqrt())).collect();
    let correlation: Vec<Vec<f64>> = (0..m)
        .map(|a| (0..m).map(|b| cov.as_ref().map_or(f64::NAN, |c| c[(a, b)] / (stat[a] * stat[b]))).collect())
        .collect();
    let covariance: Vec<Vec<f64>> = (0..m)
        .map(|a| (0..m).map(|b| cov.as_ref().map_or(f64::NAN, |c| c[(a, b)] * inflation * inflation)).collect())
        .collect();
    // profile likelihoods: each constant held, the others refitted from the optimum
    let points = problem.cal.optimiser.profile_points;
    let span = problem.cal.optimiser.profile_span;
    let profiles: Vec<Vec<ProfilePoint>> = (0..m)
        .map(|k| {
            let [lo, hi] = problem.cal.parameters[k].bounds;
            let sigma = if stat[k].is_finite() && stat[k] > 0.0 { stat[k] } else { 0.05 * (hi - lo) };
            let inner = |v: f64| v.clamp(lo + 1e-3 * (hi - lo), hi - 1e-3 * (hi - lo));
            let values: Vec<f64> = (1..=points)
                .flat_map(|i| {
                    let d = span * sigma * i as f64 / points as f64;
                    [inner(optimum[k] - d), inner(optimum[k] + d)]
                })
                .collect();
            let others: Vec<usize> = (0..m).filter(|&i| i != k).collect();
            let purpose = format!("profile:{}", problem.cal.parameters[k].key);
            let mut pts: Vec<ProfilePoint> = values
                .par_iter()
                .with_max_len(1)
                .filter_map(|&v| {
                    let mut p = optimum.clone();
                    p[k] = v;
                    let fit = optimise::minimise(problem, &p, &others, 60, &purpose)?;
                    let report = problem.run(&fit.params).ok()?;
                    let f = problem.fit(&fit.params, &report)?;
                    Some(ProfilePoint { value: v, delta_chi2: f.chi2 - chi2, params: fit.params })
                })
                .collect();
            pts.push(ProfilePoint { value: optimum[k], delta_chi2: 0.0, params: optimum.clone() });
            pts.sort_by(|a, b| a.value.total_cmp(&b.value));
            pts.dedup_by(|a, b| a.value == b.value);
            pts
        })
        .collect();

    Ok(Analysis { chi2, dof, inflation, stat, correlation, covariance, profiles })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quadratic_profile_gives_its_standard_error_on_both_sides() {
        let (opt, sd) = (2.0, 0.5);
        let point = |v: f64| ProfilePoint { value: v, delta_chi2: ((v - opt) / sd).powi(2), params: vec![v] };
        let profile: Vec<ProfilePoint> = [1.0, 1.7, 2.0, 2.4, 3.5].into_iter().map(point).collect();
        let [below, above] = profile_errors(opt, &profile);
        assert!((below - sd).abs() < 1e-12 && (above - sd).abs() < 1e-12, "{below} {above}");
        // a side without points has no error
        let [below, above] = profile_errors(opt, &profile[2..]);
        assert!(below.is_nan() && (above - sd).abs() < 1e-12);
    }
}
