//! The model a calibration fits: the base scene with its free constants set, run to its
//! end in memory (no files), and its misfit against the reference.

use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use saltus_core::scene::{apply_override, Scene};
use saltus_solvers::run::{cpu, drive, Quiet};
use saltus_solvers::{RunReport, WarmStart};

use super::reference::{self, Reference};
use super::spec::{key_error, Calibration};
use saltus_solvers::measures::bed_aligned::interpolate;

/// One model run of a calibration.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// what it was for: `start`, `minimise`, `jacobian`, `profile:<key>`, `optimum`
    pub purpose: String,
    /// the free constants
    pub params: Vec<f64>,
    /// ratio of each term's misfit to the reference's scatter (terms in misfit order;
    /// NaN for a failed run)
    pub ratios: Vec<f64>,
    /// the weighted chi^2 sum_t w_t c_t ratio_t^2 (+ the priors'); NaN for a failed run
    pub misfit: f64,
    /// the run's qs*
    pub qs_star: Option<f64>,
    /// how the run ended
    pub ending: String,
    /// steps
    pub steps: usize,
    /// CPU time of the run (s)
    pub cpu_time_s: f64,
    /// why the run failed, if it did
    pub error: Option<String>,
}

/// The misfit of one run: its residuals and terms.
#[derive(Clone, Debug)]
pub struct Fit {
    /// residuals whose sum of squares is the weighted chi^2, sum_t w_t c_t ratio_t^2 (c_t
    /// the term's independent values times the seeds; 1 times the seeds for qs*) and the
    /// priors' squares
    pub residuals: Vec<f64>,
    /// factor of each residual that makes it one of the unweighted chi^2 (its term's
    /// weight undone): the Jacobian of the covariance is scaled by it
    pub chi_scale: Vec<f64>,
    /// each term's RMS over the reference's scatter
    pub ratios: Vec<f64>,
    /// each term's RMS (profile terms) or difference (qs*), in its units
    pub rms: Vec<f64>,
    /// chi^2 of the statistical model: sum_t c_t ratio_t^2 (c_t the independent values
    /// times the seeds) and the priors'
    pub chi2: f64,
}

/// A calibration problem: the base scene's table, the reference and the misfit's form.
pub struct Problem {
    /// the loaded calibrate file
    pub cal: Calibration,
    /// the base scene resolved with the start values
    pub scene: Scene,
    /// the reference
    pub reference: Reference,
    /// the scene table every run starts from (closure tables resolved whole)
    table: toml::Table,
    /// the start values
    pub start: Vec<f64>,
    /// the profiles runs start from (a warm start), when the solver takes them
    warm: Mutex<Option<saltus_solvers::Profiles>>,
    /// every run, in order
    pub log: Mutex<Vec<Evaluation>>,
}

/// Term names of `cal`'s misfit, in order: profiles first, then qs*.
pub fn term_names(cal: &Calibration) -> Vec<String> {
    let mut t: Vec<String> = cal.misfit.terms.iter().filter(|t| t.as_str() != "qs_star").cloned().collect();
    if cal.misfit.terms.iter().any(|t| t == "qs_star") {
        t.push("qs_star".into());
    }
    t
}

fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let mut v = table.get(parts.next()?)?;
    for p in parts {
        v = v.as_table()?.get(p)?;
    }
    Some(v)
}

impl Problem {
    /// Load the base scene, check every free key against its resolved closure tables and
    /// every start against its bounds, and read the reference.
    pub fn new(cal: Calibration) -> anyhow::Result<Problem> {
        let file = &cal.file;
        let scene = Scene::from_file_with_closures(&cal.base, &cal.set, cal.closures.as_deref())
            .map_err(|e| key_error(file, "base", format!("the base scene is invalid: {e}")))?;
        if scene.solver.kind != saltus_core::scene::SolverKind::Eulerian {
            return Err(key_error(
                file,
                "base",
                "the calibrated model runs the Eulerian solver: set solver.type = \"eulerian\" (DEM runs are references)",
            ));
        }
        // the raw table with the resolved closure tables whole, so that a key the scene
        // file leaves at its default can be set alone
        let text = std::fs::read_to_string(&cal.base)?;
        let mut table = saltus_core::scene::parse_table(&text, &cal.base)?;
        if let Some(c) = &cal.closures {
            saltus_core::scene::apply_closures_file(&mut table, c)?;
        }
        for o in &cal.set {
            apply_override(&mut table, o)?;
        }
        let resolved = saltus_core::scene::parse_table(&scene.to_toml()?, &cal.base)?;
        let closures = resolved.get("closures").cloned().unwrap_or(toml::Value::Table(toml::Table::new()));
        table.insert("closures".into(), closures);
        if let Some(s) = table.get_mut("solver").and_then(|s| s.as_table_mut()) {
            for face in saltus_core::scene::FACES {
                if let Some(f) = s.get_mut(face).and_then(|f| f.as_table_mut()) {
                    f.remove("closures");
                }
            }
        }
        let mut start = Vec::new();
        for (i, p) in cal.parameters.iter().enumerate() {
            let key = format!("parameter[{i}].key");
            let value = match lookup(&table, &p.key) {
                Some(toml::Value::Float(v)) => *v,
                Some(toml::Value::Integer(v)) => *v as f64,
                Some(other) => {
                    return Err(key_error(
                        file,
                        key,
                        format!("`{}` holds {} in the base scene, not a number", p.key, other.type_str()),
                    ))
                }
                None => {
                    let parent = p.key.rsplit_once('.').map_or("", |(a, _)| a);
                    let keys: Vec<String> = match lookup(&table, parent) {
                        Some(toml::Value::Table(t)) => {
                            t.iter().filter(|(_, v)| v.is_float() || v.is_integer()).map(|(k, _)| k.clone()).collect()
                        }
                        _ => Vec::new(),
                    };
                    return Err(key_error(
                        file,
                        key,
                        format!(
                            "`{}` is not a closure key of the base scene; the numeric keys of `{parent}` are {keys:?}",
                            p.key
                        ),
                    ));
                }
            };
            let s = p.start.unwrap_or(value);
            let [lo, hi] = p.bounds;
            if !(s > lo && s < hi) {
                return Err(key_error(
                    file,
                    format!("parameter[{i}].bounds"),
                    format!("[{lo}, {hi}] exclude the start {s} (the base scene's `{}`)", p.key),
                ));
            }
            if !super::bounds::resolves(s, p.bounds) {
                return Err(key_error(
                    file,
                    format!("parameter[{i}].bounds"),
                    format!(
                        "[{lo}, {hi}] are too wide for the start {s} of `{}`: the bounded search cannot resolve it; \
                         give bounds within a few orders of magnitude of the start",
                        p.key
                    ),
                ));
            }
            start.push(s);
        }
        let reference = reference::load(&cal, &scene)?;
        let problem =
            Problem { cal, scene, reference, table, start, warm: Mutex::new(None), log: Mutex::new(Vec::new()) };
        // a start the closures refuse (a value outside a closure's range) fails here
        problem.scene_at(&problem.start)?;
        // and so does a bound: the optimiser may step to either end of each range
        for (i, par) in problem.cal.parameters.iter().enumerate() {
            for bound in par.bounds {
                let mut p = problem.start.clone();
                p[i] = bound;
                if let Err(e) = problem.scene_at(&p) {
                    return Err(key_error(
                        &problem.cal.file,
                        format!("parameter[{i}].bounds"),
                        format!(
                            "[{}, {}]: the closure refuses `{}` = {bound}, so the optimiser could not reach that bound: {e}",
                            par.bounds[0], par.bounds[1], par.key
                        ),
                    ));
                }
            }
        }
        Ok(problem)
    }

    /// The scene with the free constants `p`.
    pub fn scene_at(&self, p: &[f64]) -> anyhow::Result<Scene> {
        let mut t = self.table.clone();
        for (par, v) in self.cal.parameters.iter().zip(p) {
            apply_override(&mut t, &format!("{}={v:?}", par.key))?;
        }
        let scene = Scene::from_table(t, &self.cal.base)?;
        saltus_solvers::validate(&scene)?;
        Ok(scene)
    }

    /// Make the profiles of `p`'s run the start of every later run (a warm start).
    pub fn anchor(&self, p: &[f64]) {
        let report = self.run(p).ok();
        if let Ok(mut w) = self.warm.lock() {
            *w = report.map(|r| r.profiles);
        }
    }

    /// Run the model at `p`, warm from the anchor's profiles where the solver takes them.
    pub fn run(&self, p: &[f64]) -> anyhow::Result<RunReport> {
        let scene = self.scene_at(p)?;
        let mut stepper = saltus_solvers::resolve(&scene)?;
        let warm = self.warm.lock().ok().and_then(|w| w.clone());
        if let Some(profiles) = warm {
            // a solver that cannot take profiles (k-omega's k and omega) starts from rest
            let _ = stepper.warm_start(&WarmStart::Profiles(profiles));
        }
        let driven = drive(stepper.as_mut(), &mut Quiet);
        let report = stepper.report(&driven.ending, &driven.clock);
        if matches!(driven.ending, saltus_solvers::Ending::Unstable(_)) {
            anyhow::bail!("the run went unstable: {}", report.summary.ending);
        }
        Ok(report)
    }

    /// The misfit of a run's report.
    pub fn fit(&self, p: &[f64], report: &RunReport) -> Option<Fit> {
        let shaped = self.reference.shape(&report.profiles)?;
        let weight = |t: &str| self.cal.misfit.weights.get(t).copied().unwrap_or(1.0);
        let seeds = self.reference.seeds as f64;
        let mut f =
            Fit { residuals: Vec::new(), chi_scale: Vec::new(), ratios: Vec::new(), rms: Vec::new(), chi2: 0.0 };
        for term in &self.reference.profiles {
            let (z, v) = (shaped.get("z")?, shaped.get(&term.name)?);
            let held;
            let v = if term.name == "u_p" {
                held = velocity_of_grains(shaped.get("phi")?, v);
                &held[..]
            } else {
                v
            };
            let n = term.z.len() as f64;
            let c = seeds * term.independent;
            let scale = (weight(&term.name) * c / n).sqrt() / term.scatter;
            let mut ss = 0.0;
            for (zi, m) in term.z.iter().zip(&term.mean) {
                let d = interpolate(z, v, *zi) - m;
                ss += d * d;
                f.residuals.push(scale * d);
            }
            f.chi_scale.extend(std::iter::repeat_n(weight(&term.name).sqrt().recip(), term.z.len()));
            let rms = (ss / n).sqrt();
            let ratio = rms / term.scatter;
            f.rms.push(rms);
            f.ratios.push(ratio);
            f.chi2 += c * ratio * ratio;
        }
        if let Some(rate) = &self.reference.rate {
            let d = report.summary.qs_star? - rate.mean;
            let ratio = d.abs() / rate.scatter;
            f.residuals.push((weight("qs_star") * seeds).sqrt() * d / rate.scatter);
            f.chi_scale.push(weight("qs_star").sqrt().recip());
            f.rms.push(d);
            f.ratios.push(ratio);
            f.chi2 += seeds * ratio * ratio;
        }
        for (par, v) in self.cal.parameters.iter().zip(p) {
            if let Some(pr) = &par.prior {
                let r = (v - pr.mean) / pr.sd;
                f.residuals.push(r);
                f.chi_scale.push(1.0);
                f.chi2 += r * r;
            }
        }
        f.residuals.iter().all(|r| r.is_finite()).then_some(f)
    }

    /// Residuals at `p` (run, misfit, logged under `purpose`); `None` for a run that
    /// failed or a misfit that is not finite.
    pub fn evaluate(&self, p: &[f64], purpose: &str) -> Option<Fit> {
        let cpu0 = cpu::thread_seconds();
        let started = Instant::now();
        let outcome = self.run(p);
        let cpu_time_s = match (cpu0, cpu::thread_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => started.elapsed().as_secs_f64(),
        };
        let fit = outcome.as_ref().ok().and_then(|r| self.fit(p, r));
        let terms = term_names(&self.cal).len();
        let e = Evaluation {
            purpose: purpose.to_string(),
            params: p.to_vec(),
            ratios: fit.as_ref().map_or_else(|| vec![f64::NAN; terms], |f| f.ratios.clone()),
            misfit: fit.as_ref().map_or(f64::NAN, |f| f.residuals.iter().map(|r| r * r).sum()),
            qs_star: outcome.as_ref().ok().and_then(|r| r.summary.qs_star),
            ending: outcome.as_ref().map_or_else(|_| "failed".into(), |r| r.summary.ending.clone()),
            steps: outcome.as_ref().map_or(0, |r| r.summary.steps),
            cpu_time_s,
            error: match (&outcome, &fit) {
                (Err(e), _) => Some(format!("{e:#}")),
                (Ok(_), None) => Some("no finite misfit (no profile to compare)".into()),
                _ => None,
            },
        };
        if let Ok(mut log) = self.log.lock() {
            log.push(e);
        }
        fit
    }

    /// The calibrate file, for messages.
    pub fn file(&self) -> &Path {
        &self.cal.file
    }
}

/// Volume fraction below which a model cell holds no grains: far below a suspension's
/// and below one grain in any DEM slice; the two-fluid column's empty cells sit at 1e-300.
const PHI_EMPTY: f64 = 1e-9;

/// `u_p` where the column holds grains, and above them the velocity of the highest cell
/// that does: an empty cell's particle velocity is not a velocity of grains (in a dry
/// column it is the free fall of nothing, hundreds of m/s after seconds), and the phi term
/// already counts the grains the model lacks there.
fn velocity_of_grains(phi: &[f64], u_p: &[f64]) -> Vec<f64> {
    let mut last = None;
    let held: Vec<Option<f64>> = phi
        .iter()
        .zip(u_p)
        .map(|(&f, &u)| {
            if f > PHI_EMPTY {
                last = Some(u);
            }
            last
        })
        .collect();
    // below the lowest cell with grains (none in a column with a bed) the first one's
    let first = held.iter().flatten().next().copied();
    held.into_iter().zip(u_p).map(|(h, &u)| h.or(first).unwrap_or(u)).collect()
}

#[cfg(test)]
mod tests {
    use super::velocity_of_grains;

    #[test]
    fn an_empty_cell_takes_the_velocity_of_the_grains_below() {
        let phi = [0.0, 0.5, 0.3, 1e-300, 0.0, 1e-3];
        let u = [7.0, 0.1, 0.4, 50.0, 90.0, 0.6];
        assert_eq!(velocity_of_grains(&phi, &u), [0.1, 0.1, 0.4, 0.4, 0.4, 0.6]);
        assert_eq!(velocity_of_grains(&[0.0, 0.0], &[1.0, 2.0]), [1.0, 2.0]);
    }
}
