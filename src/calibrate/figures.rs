//! The figures of a calibration, as [`crate::figures`] draws them: the profiles at the
//! start and at the optimum over the reference with its scatter band, and the profile
//! likelihoods.

use std::path::{Path, PathBuf};

use anyhow::Context;
use saltus_solvers::{Profiles, RunReport};

use super::model::Problem;
use super::CalibrationReport;
use crate::figures;
use crate::figures::likelihood::Constant;
use crate::figures::profiles::{Columns, Reference, PHI_PANEL, U_P_PANEL};
use crate::table::Table;

/// Profiles of phi and u_p (shaped as the reference's: smoothed, from the bed surface)
/// at the start and at the optimum, the reference's mean as symbols and its mean +- one
/// seed's scatter as thin curves.
pub fn profiles(problem: &Problem, start: &RunReport, optimum: &RunReport, png: &Path) -> anyhow::Result<PathBuf> {
    let r = &problem.reference;
    let shaped = |rep: &RunReport| r.shape(&rep.profiles).context("a run without profiles to shape");
    let (a, b) = (shaped(start)?, shaped(optimum)?);
    let mut tables = Vec::new();
    let mut bands: Vec<(String, Profiles)> = Vec::new();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for t in &r.profiles {
        let mut table = Table::default();
        table.push("z", t.z.clone());
        table.push(t.name.clone(), t.mean.clone());
        tables.push(table);
        for (sign, label) in [(-1.0, "reference - scatter"), (1.0, "reference + scatter")] {
            let mut p = Profiles::default();
            p.push("z", t.z.clone());
            p.push(&t.name, t.mean.iter().map(|m| m + sign * t.scatter).collect());
            bands.push((label.to_string(), p));
        }
        lo = lo.min(t.z[0]);
        hi = hi.max(t.z[t.z.len() - 1]);
    }
    let pad = 0.3 * (hi - lo).max(1e-3);
    let mut curves: Vec<(String, &dyn Columns)> = vec![("start".into(), &a), ("optimum".into(), &b)];
    curves.extend(bands.iter().map(|(l, p)| (l.clone(), p as &dyn Columns)));
    let references: Vec<Reference> =
        tables.iter().map(|table| Reference { label: "reference (mean)", table }).collect();
    let z = match (&r.data_bed, r.align) {
        (Some(_), _) => ", the run's bed surface on the data's",
        (None, true) => ", z from the bed surface",
        (None, false) => "",
    };
    let title = format!("start, optimum and reference{z}");
    figures::profiles::draw_columns(
        &title,
        &[PHI_PANEL, U_P_PANEL],
        &curves,
        &references,
        Some((lo - pad, hi + pad)),
        png,
    )?;
    Ok(png.to_path_buf())
}

/// One panel per constant: chi^2 - chi^2_min with the others refitted (symbols) and the
/// Laplace approximation ((p - p_opt) / stderr_statistical)^2 (line).
pub fn likelihood(r: &CalibrationReport, png: &Path) -> anyhow::Result<PathBuf> {
    let constants: Vec<Constant> = r
        .fitted
        .iter()
        .map(|f| Constant {
            key: &f.key,
            value: f.value,
            stderr: f.stderr_statistical,
            profile: f.profile.iter().map(|p| (p.value, p.delta_chi2)).collect(),
        })
        .collect();
    figures::likelihood::draw(&constants, png)?;
    Ok(png.to_path_buf())
}
