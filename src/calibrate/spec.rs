//! The calibrate file: its keys, read and checked before any run.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use saltus_core::scene::Meta;
use serde::Deserialize;

use crate::study_file;
pub(super) use crate::study_file::key_error;

/// Misfit terms a calibration may use.
pub const TERMS: [&str; 3] = ["phi", "u_p", "qs_star"];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    base: String,
    #[serde(default)]
    meta: Meta,
    #[serde(default)]
    set: Vec<String>,
    #[serde(default)]
    closures: Option<PathBuf>,
    #[serde(default, rename = "parameter")]
    parameters: Vec<Parameter>,
    reference: ReferenceSpec,
    #[serde(default)]
    misfit: MisfitSpec,
    #[serde(default)]
    optimiser: OptimiserSpec,
}

/// One free constant: a numeric key of a closure table of the base scene.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// the key, as `--set` writes it (`closures.granular.g0.a0`)
    pub key: String,
    /// lower and upper bound
    pub bounds: [f64; 2],
    /// first value (default: the base scene's)
    #[serde(default)]
    pub start: Option<f64>,
    /// a Gaussian prior on the constant
    #[serde(default)]
    pub prior: Option<Prior>,
}

/// A Gaussian prior: one more residual (value - mean) / sd.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Prior {
    /// mean
    pub mean: f64,
    /// standard deviation
    pub sd: f64,
}

/// What the model is measured against.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// run folders (each with `profiles.csv` and `summary.json`), one per seed, relative to
    /// the calibrate file
    #[serde(default)]
    pub runs: Vec<PathBuf>,
    /// the base scene's reference data (`[[reference]]`) instead of runs
    #[serde(default)]
    pub data: bool,
    /// a published qs* (with `data`)
    #[serde(default)]
    pub qs_star: Option<f64>,
    /// Fry et al. 2024 eq-11 Gaussian of h_g = `smooth` grain diameters (runs only)
    #[serde(default)]
    pub smooth: Option<f64>,
    /// each run's profiles from its own bed surface; with data, the model shifted so that
    /// its bed surface (phi at half its bed value) sits on the data's
    #[serde(default)]
    pub align: bool,
    /// the scatter of each term, in its units, where the reference cannot give it (one
    /// run, data): `{ phi = 0.02, u_p = 0.03, qs_star = 0.05 }`
    #[serde(default)]
    pub scatter: std::collections::BTreeMap<String, f64>,
    /// distance (grain diameters) over which the reference's rows are correlated: a
    /// profile term counts one independent value per this length of its layer
    #[serde(default)]
    pub correlation_length: Option<f64>,
    /// grain diameters of the bed below the moving layer whose rows the profile terms take
    /// in as well (default 0): a model whose bed creeps or packs where the reference's
    /// rests is then seen; the scatter stays that of the moving layer
    #[serde(default)]
    pub bed_depth: Option<f64>,
}

/// Which terms the misfit sums and how each weighs.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MisfitSpec {
    /// terms, of [`TERMS`]
    pub terms: Vec<String>,
    /// weight of each term (default 1)
    #[serde(default)]
    pub weights: std::collections::BTreeMap<String, f64>,
}

impl Default for MisfitSpec {
    fn default() -> Self {
        Self { terms: vec!["phi".into(), "u_p".into()], weights: Default::default() }
    }
}

/// The optimiser's settings.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct OptimiserSpec {
    /// most model runs of the minimisation (the covariance and profiles come after)
    pub max_evaluations: usize,
    /// relative reduction of the misfit and relative step below which it stops
    pub tolerance: f64,
    /// central-difference step of the Jacobian, as a fraction of the parameter's bounds
    pub step: f64,
    /// points on each side of the optimum of each profile likelihood (0: none)
    pub profile_points: usize,
    /// span of a profile likelihood, in standard errors each side
    pub profile_span: f64,
}

impl Default for OptimiserSpec {
    fn default() -> Self {
        Self { max_evaluations: 400, tolerance: 1e-6, step: 1e-3, profile_points: 3, profile_span: 3.0 }
    }
}

/// A loaded and checked calibrate file.
#[derive(Clone, Debug)]
pub struct Calibration {
    /// the calibrate file
    pub file: PathBuf,
    /// base scene
    pub base: PathBuf,
    /// name (never empty) and description
    pub meta: Meta,
    /// overrides of every run (the file's, then the command line's)
    pub set: Vec<String>,
    /// closures file replacing the base scene's tables, before the overrides
    pub closures: Option<PathBuf>,
    /// free constants, at least one
    pub parameters: Vec<Parameter>,
    /// reference, runs resolved against the file's folder
    pub reference: ReferenceSpec,
    /// misfit
    pub misfit: MisfitSpec,
    /// optimiser
    pub optimiser: OptimiserSpec,
}

fn finite_positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// Read and check a calibrate file: keys, bounds, terms, weights and the reference's
/// form; the parameters' keys and the reference's contents are checked against the base
/// scene by [`super::Problem::new`].
pub fn load(path: &Path, set: &[String]) -> anyhow::Result<Calibration> {
    let (raw, folder): (RawFile, _) = study_file::read(path)?;
    if raw.parameters.is_empty() {
        return Err(key_error(
            path,
            "parameter",
            "no [[parameter]] table; give at least one, each with key and bounds",
        ));
    }
    let mut keys = HashSet::new();
    for (i, p) in raw.parameters.iter().enumerate() {
        let at = |k: &str| format!("parameter[{i}].{k}");
        if !p.key.starts_with("closures.") || p.key.split('.').count() < 3 {
            return Err(key_error(
                path,
                at("key"),
                format!("`{}`: a free parameter is a key of a closure table, `closures.<family>.<key>`", p.key),
            ));
        }
        if !keys.insert(p.key.as_str()) {
            return Err(key_error(path, at("key"), format!("`{}` is freed by an earlier parameter", p.key)));
        }
        let [lo, hi] = p.bounds;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(key_error(path, at("bounds"), format!("[{lo}, {hi}]: two finite numbers, the lower first")));
        }
        if let Some(s) = p.start.filter(|s| !(s.is_finite() && *s > lo && *s < hi)) {
            return Err(key_error(
                path,
                at("start"),
                format!("{s} for `{}`: must lie inside its bounds ({lo}, {hi})", p.key),
            ));
        }
        if let Some(pr) = &p.prior {
            if !pr.mean.is_finite() || !finite_positive(pr.sd) {
                return Err(key_error(path, at("prior"), "mean a finite number, sd a finite number > 0"));
            }
        }
    }
    let mut reference = raw.reference;
    let r = &reference;
    match (r.runs.is_empty(), r.data) {
        (true, false) => {
            return Err(key_error(path, "reference", "give runs = [\"<run folder>\", ...] or data = true"));
        }
        (false, true) => return Err(key_error(path, "reference", "either runs or data, not both")),
        _ => {}
    }
    if r.data && r.smooth.is_some() {
        return Err(key_error(path, "reference.smooth", "smooth shapes the profiles of runs, not data"));
    }
    if r.qs_star.is_some() && !r.data {
        return Err(key_error(path, "reference.qs_star", "a published qs* goes with data = true; runs give their own"));
    }
    if let Some(q) = r.qs_star.filter(|q| !finite_positive(*q)) {
        return Err(key_error(path, "reference.qs_star", format!("{q}: a finite number > 0")));
    }
    crate::compare::precision::check_smooth(path, r.smooth)?;
    if let Some(l) = r.correlation_length.filter(|l| !(finite_positive(*l) && *l <= 1e3)) {
        return Err(key_error(path, "reference.correlation_length", format!("{l}: grain diameters, > 0 and <= 1000")));
    }
    if let Some(b) = r.bed_depth.filter(|b| !(b.is_finite() && *b >= 0.0 && *b <= 1e3)) {
        return Err(key_error(path, "reference.bed_depth", format!("{b}: grain diameters, >= 0 and <= 1000")));
    }
    for (k, v) in &r.scatter {
        if !TERMS.contains(&k.as_str()) {
            return Err(key_error(path, format!("reference.scatter.{k}"), format!("not a term; one of {TERMS:?}")));
        }
        if !finite_positive(*v) {
            return Err(key_error(path, format!("reference.scatter.{k}"), format!("{v}: a finite number > 0")));
        }
    }
    if raw.misfit.terms.is_empty() {
        return Err(key_error(path, "misfit.terms", format!("no term; one or more of {TERMS:?}")));
    }
    let mut seen = HashSet::new();
    for t in &raw.misfit.terms {
        if !TERMS.contains(&t.as_str()) {
            return Err(key_error(path, "misfit.terms", format!("`{t}` is not a term; one of {TERMS:?}")));
        }
        if !seen.insert(t.as_str()) {
            return Err(key_error(path, "misfit.terms", format!("`{t}` is given twice")));
        }
    }
    for (k, w) in &raw.misfit.weights {
        if !raw.misfit.terms.contains(k) {
            return Err(key_error(path, format!("misfit.weights.{k}"), "the weight of a term that misfit.terms lacks"));
        }
        if !finite_positive(*w) {
            return Err(key_error(path, format!("misfit.weights.{k}"), format!("{w}: a finite number > 0")));
        }
    }
    let o = &raw.optimiser;
    if o.max_evaluations == 0 || o.max_evaluations > 1_000_000 {
        return Err(key_error(path, "optimiser.max_evaluations", format!("{}: 1 to 1000000", o.max_evaluations)));
    }
    if !(finite_positive(o.tolerance) && o.tolerance < 1.0) {
        return Err(key_error(path, "optimiser.tolerance", format!("{}: a number in (0, 1)", o.tolerance)));
    }
    if !(finite_positive(o.step) && o.step <= 0.1) {
        return Err(key_error(path, "optimiser.step", format!("{}: a fraction of the bounds in (0, 0.1]", o.step)));
    }
    if o.profile_points > 50 {
        return Err(key_error(path, "optimiser.profile_points", format!("{}: 0 to 50", o.profile_points)));
    }
    if !(finite_positive(o.profile_span) && o.profile_span <= 100.0) {
        return Err(key_error(path, "optimiser.profile_span", format!("{}: in (0, 100]", o.profile_span)));
    }
    let base = study_file::base_scene(path, &raw.base)?;
    let closures = raw.closures.map(|c| study_file::closures_file(path, "closures", &c)).transpose()?;
    for (i, run) in reference.runs.iter_mut().enumerate() {
        *run = folder.join(&*run);
        if !run.join(crate::run_files::PROFILES).is_file() {
            return Err(key_error(
                path,
                format!("reference.runs[{i}]"),
                format!("{}: no run folder with profiles.csv", run.display()),
            ));
        }
    }
    let meta = study_file::named(raw.meta, path, "calibration");
    let mut sets = raw.set;
    sets.extend(set.iter().cloned());
    Ok(Calibration {
        file: path.to_path_buf(),
        base,
        meta,
        set: sets,
        closures,
        parameters: raw.parameters,
        reference,
        misfit: raw.misfit,
        optimiser: raw.optimiser,
    })
}
