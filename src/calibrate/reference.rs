//! The reference of a calibration: the mean of several runs (seeds) or the base scene's
//! data, each misfit term with its scatter.
//!
//! A profile term (phi, u_p) is the reference's mean profile over the rows where its
//! grains move (the moving layer of `precision.csv`), with the scatter s of one seed about
//! that mean: the pooled standard deviation of the seeds, sqrt(mean over the rows of
//! sd_i^2), sd_i the sample standard deviation of the N seeds at row i. With one run or
//! data, s is the file's `scatter`. The qs* term is the seeds' mean with their sample
//! standard deviation, or the RMS of the runs' own standard errors where that is larger (a
//! seed scatters at least by its time-averaging error; two seeds can agree far closer by
//! chance); one run: its own standard error; data: `qs_star` with `scatter`. A `scatter`
//! given in the file replaces the runs' own.
//!
//! A run's rate enters as its qs (m^2/s) on the base scene's scale sqrt((s - 1) g d^3),
//! not as the qs* of its own summary: a reference run in another fluid than the model (a
//! dry DEM, whose summary divides by the density contrast of an unused fluid, against a
//! two-fluid column in air) is compared by its transport rate.

use std::path::Path;

use anyhow::Context;
use saltus_core::scene::Scene;
use saltus_solvers::measures::bed_aligned::interpolate;
use saltus_solvers::{Profiles, Summary};

use super::spec::{key_error, Calibration};
use crate::compare::precision::{moving_rows, prepared};
use crate::run_files;

/// One profile term of the reference.
#[derive(Clone, Debug)]
pub struct ProfileTerm {
    /// `phi` or `u_p`
    pub name: String,
    /// heights of the rows (above the bed surface when aligned), m
    pub z: Vec<f64>,
    /// the reference's value at each row (the seeds' mean)
    pub mean: Vec<f64>,
    /// the seeds' standard deviation at each row (0 with one run or data)
    pub sd: Vec<f64>,
    /// scatter of one seed about the mean over the rows
    pub scatter: f64,
    /// independent values the rows hold: the layer's thickness over the correlation length
    pub independent: f64,
}

/// The qs* term of the reference.
#[derive(Clone, Copy, Debug)]
pub struct RateTerm {
    /// the seeds' mean (or the published value)
    pub mean: f64,
    /// scatter of one seed (or the given scatter)
    pub scatter: f64,
}

/// The reference of a calibration.
#[derive(Clone, Debug)]
pub struct Reference {
    /// profile terms, in misfit order
    pub profiles: Vec<ProfileTerm>,
    /// the qs* term, when the misfit has it
    pub rate: Option<RateTerm>,
    /// runs (seeds) whose mean it is; 1 for data
    pub seeds: usize,
    /// Gaussian width h_g (m) the profiles are smoothed with (0: none)
    pub h_g: f64,
    /// profiles taken from their bed surfaces
    pub align: bool,
    /// the seeds' own shaped profiles (z, phi, u_p), for the figure
    pub members: Vec<Profiles>,
    /// the data's phi profile (z, phi) whose bed surface an aligned model is shifted onto
    pub data_bed: Option<(Vec<f64>, Vec<f64>)>,
}

impl Reference {
    /// The model's profile `p` shaped as the reference's are (smoothed, aligned); `None`
    /// when it cannot be (no z, phi, u_p; no flux to align on).
    pub fn shape(&self, p: &Profiles) -> Option<Profiles> {
        if let Some((dz, dphi)) = &self.data_bed {
            // data: the run shifted rigidly so that its bed surface sits on the data's, as
            // the compare table's bed-aligned differences are taken
            let (z, phi) = (p.get("z")?, p.get("phi")?);
            let shift = saltus_solvers::measures::bed_aligned::shift(z, phi, dz, dphi)?;
            let mut out = p.clone();
            if let Some((_, v)) = out.columns.iter_mut().find(|(n, _)| n == "z") {
                v.iter_mut().for_each(|z| *z -= shift);
            }
            return Some(out);
        }
        if self.h_g > 0.0 || self.align {
            prepared(p, self.h_g, self.align)
        } else {
            Some(p.clone())
        }
    }
}

fn read_run(dir: &Path) -> anyhow::Result<(Profiles, Summary)> {
    let p = run_files::profiles(dir)?;
    let s = run_files::summary(dir)?.with_context(|| format!("{}: missing", dir.join(run_files::SUMMARY).display()))?;
    Ok((p, s))
}

fn mean_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = if values.len() > 1 { values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0) } else { 0.0 };
    (mean, var.sqrt())
}

/// The reference of `cal` for the base scene `scene` (its grain diameter, its data).
pub fn load(cal: &Calibration, scene: &Scene) -> anyhow::Result<Reference> {
    let spec = &cal.reference;
    let d = scene.particles.diameter;
    let h_g = spec.smooth.unwrap_or(0.0) * d;
    let ell = spec.correlation_length.unwrap_or(1.0).max(spec.smooth.unwrap_or(0.0)) * d;
    let bed = spec.bed_depth.unwrap_or(0.0) * d;
    let wants = |t: &str| cal.misfit.terms.iter().any(|m| m == t);
    let given = |t: &str| spec.scatter.get(t).copied();
    let refuse = |key: String, m: String| key_error(&cal.file, key, m);
    let mut reference = Reference {
        profiles: Vec::new(),
        rate: None,
        seeds: 1,
        h_g,
        align: spec.align,
        members: Vec::new(),
        data_bed: None,
    };
    if spec.data {
        let tables = crate::runner::load_reference(scene)
            .map_err(|e| refuse("reference.data".into(), format!("the base scene's reference data: {e:#}")))?;
        for name in ["phi", "u_p"].into_iter().filter(|t| wants(t)) {
            let Some((_, t)) = tables.iter().find(|(_, t)| t.get(name).is_some()) else {
                return Err(refuse(
                    "reference.data".into(),
                    format!("no reference file of the base scene has `{name}`"),
                ));
            };
            let (z, v) = (t.get("z").unwrap_or_default(), t.get(name).unwrap_or_default());
            // the rows where the data say grains move: phi and u_p of their own files,
            // interpolated onto this term's rows
            let column = |c: &str| tables.iter().find_map(|(_, t)| Some((t.get("z")?, t.get(c)?)));
            let at = |c: &str, zi: f64| column(c).map(|(zc, fc)| interpolate(zc, fc, zi));
            let phi: Vec<f64> = z.iter().map(|&zi| at("phi", zi).unwrap_or(1.0)).collect();
            let u: Vec<f64> = z.iter().map(|&zi| at("u_p", zi).unwrap_or(1.0)).collect();
            let keep = with_bed(&moving_rows(z, &phi, &u), z, bed);
            let keep: Vec<usize> = keep.into_iter().filter(|&k| v[k].is_finite()).collect();
            let scatter = given(name).ok_or_else(|| {
                refuse(
                    format!("reference.scatter.{name}"),
                    "data carry no scatter: give the measurements' error".into(),
                )
            })?;
            reference.profiles.push(term(name, &keep, z, v, vec![0.0; z.len()], scatter, ell)?);
        }
        if wants("qs_star") {
            let q = spec
                .qs_star
                .ok_or_else(|| refuse("reference.qs_star".into(), "the qs_star term needs a published qs*".into()))?;
            let s = given("qs_star")
                .ok_or_else(|| refuse("reference.scatter.qs_star".into(), "a published qs* needs its error".into()))?;
            reference.rate = Some(RateTerm { mean: q, scatter: s });
        }
        if spec.align {
            let (z, phi) = tables.iter().find_map(|(_, t)| Some((t.get("z")?, t.get("phi")?))).ok_or_else(|| {
                refuse(
                    "reference.align".into(),
                    "no reference file of the base scene has `phi`, whose bed surface the model is aligned on".into(),
                )
            })?;
            if saltus_solvers::measures::bed_aligned::half_bed_level(z, phi).is_none() {
                return Err(refuse(
                    "reference.align".into(),
                    "the data's phi has no bed surface (no level where it falls to half its bottom value)".into(),
                ));
            }
            reference.data_bed = Some((z.to_vec(), phi.to_vec()));
        }
        return Ok(reference);
    }
    let mut runs = Vec::new();
    for (i, dir) in spec.runs.iter().enumerate() {
        let key = format!("reference.runs[{i}]");
        let (p, s) = read_run(dir).map_err(|e| refuse(key.clone(), format!("{e:#}")))?;
        let shaped = reference.shape(&p).ok_or_else(|| {
            refuse(key.clone(), format!("{}: no z, phi and u_p profile (or no flux to align on)", dir.display()))
        })?;
        runs.push((shaped, s));
    }
    reference.seeds = runs.len();
    let n = runs.len();
    // every seed on the first one's rows
    let z = runs[0].0.get("z").unwrap_or_default().to_vec();
    let on_rows = |name: &str| -> Vec<Vec<f64>> {
        runs.iter()
            .map(|(p, _)| {
                let (zp, f) = (p.get("z").unwrap_or_default(), p.get(name).unwrap_or_default());
                z.iter().map(|&zi| interpolate(zp, f, zi)).collect()
            })
            .collect()
    };
    let (phi_seeds, u_seeds) = (on_rows("phi"), on_rows("u_p"));
    let stats = |seeds: &[Vec<f64>]| -> (Vec<f64>, Vec<f64>) {
        (0..z.len()).map(|k| mean_sd(&seeds.iter().map(|s| s[k]).collect::<Vec<_>>())).unzip()
    };
    let (phi_mean, phi_sd) = stats(&phi_seeds);
    let (u_mean, u_sd) = stats(&u_seeds);
    let keep = moving_rows(&z, &phi_mean, &u_mean);
    if keep.is_empty() {
        return Err(refuse("reference.runs".into(), "the runs' mean has no row where grains move".into()));
    }
    for (name, mean, sd) in [("phi", &phi_mean, &phi_sd), ("u_p", &u_mean, &u_sd)] {
        if !wants(name) {
            continue;
        }
        let pooled = (keep.iter().map(|&k| sd[k] * sd[k]).sum::<f64>() / keep.len() as f64).sqrt();
        let scatter = match (given(name), n) {
            (Some(s), _) => s,
            (None, 1) => {
                return Err(refuse(
                    format!("reference.scatter.{name}"),
                    "one run has no seed scatter: give more runs (seeds) or the scatter".into(),
                ))
            }
            (None, _) => pooled,
        };
        if !(scatter > 0.0 && scatter.is_finite()) {
            return Err(refuse(
                format!("reference.scatter.{name}"),
                format!("the runs' scatter of {name} over the moving layer is {scatter} (identical runs?): give it"),
            ));
        }
        reference.profiles.push(term(name, &with_bed(&keep, &z, bed), &z, mean, sd.clone(), scatter, ell)?);
    }
    if wants("qs_star") {
        let depth = scene.domain.water_depth;
        let scale =
            saltus_solvers::measures::transport_scales::TransportScales::new(scene, scene.particles.density, d, depth)
                .qs;
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(refuse(
                "misfit.terms".into(),
                "qs_star: the base scene has no transport scale (no gravity or no density contrast)".into(),
            ));
        }
        let q: Vec<f64> = runs.iter().filter_map(|(_, s)| s.qs).map(|q| q / scale).collect();
        if q.len() != n {
            return Err(refuse("reference.runs".into(), "a run's summary has no qs".into()));
        }
        let stderr = |s: &Summary| s.qs_stderr.map(|e| e / scale);
        let (mean, sd) = mean_sd(&q);
        let own = stderr(&runs[0].1);
        let scatter = match (given("qs_star"), n, own) {
            (Some(s), _, _) => s,
            (None, 1, Some(e)) => e,
            (None, 1, None) => {
                return Err(refuse(
                    "reference.scatter.qs_star".into(),
                    "one run without a standard error of qs*: give more runs or the scatter".into(),
                ))
            }
            // a seed's scatter is at least its own time-averaging error: with few seeds
            // their sample deviation can fall far below it by chance
            (None, _, _) => {
                let errors: Vec<f64> = runs.iter().filter_map(|(_, s)| stderr(s)).collect();
                let floor = if errors.is_empty() {
                    0.0
                } else {
                    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
                };
                sd.max(floor)
            }
        };
        if !(scatter > 0.0 && scatter.is_finite()) {
            return Err(refuse(
                "reference.scatter.qs_star".into(),
                format!("the runs' scatter of qs* is {scatter} (identical runs?): give it"),
            ));
        }
        reference.rate = Some(RateTerm { mean, scatter });
    }
    reference.members = runs.into_iter().map(|(p, _)| p).collect();
    Ok(reference)
}

/// `keep` (rows in ascending z) and the rows of `z` within `depth` below its lowest.
fn with_bed(keep: &[usize], z: &[f64], depth: f64) -> Vec<usize> {
    let Some(&first) = keep.first() else {
        return Vec::new();
    };
    let bottom = z[first] - depth;
    let mut rows: Vec<usize> = (0..z.len()).filter(|&k| z[k] >= bottom && z[k] < z[first]).collect();
    rows.extend_from_slice(keep);
    rows
}

fn term(
    name: &str,
    keep: &[usize],
    z: &[f64],
    mean: &[f64],
    sd: Vec<f64>,
    scatter: f64,
    ell: f64,
) -> anyhow::Result<ProfileTerm> {
    if keep.is_empty() {
        anyhow::bail!("the reference's `{name}` has no row where grains move");
    }
    let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<_>>();
    let zs = pick(z);
    // the layer's thickness: its rows' span and one row's height
    let row = if zs.len() > 1 { (zs[zs.len() - 1] - zs[0]) / (zs.len() - 1) as f64 } else { ell };
    let thickness = zs[zs.len() - 1] - zs[0] + row;
    Ok(ProfileTerm {
        name: name.to_string(),
        independent: (thickness / ell).max(1.0),
        mean: pick(mean),
        sd: pick(&sd),
        z: zs,
        scatter,
    })
}
