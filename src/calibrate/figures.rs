//! The figures of a calibration: the profiles at the start and at the optimum over the
//! reference with its scatter band, and the profile likelihoods.

use std::path::{Path, PathBuf};

use anyhow::Context;
use plotters::prelude::*;
use saltus_solvers::{Profiles, RunReport};

use super::model::Problem;
use super::CalibrationReport;
use crate::plot::{self, register_font, Columns, Reference, COLORS, PHI_PANEL, U_P_PANEL};
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
    plot::draw_columns(&title, &[PHI_PANEL, U_P_PANEL], &curves, &references, Some((lo - pad, hi + pad)), png)?;
    Ok(png.to_path_buf())
}

/// One panel per constant: chi^2 - chi^2_min with the others refitted (symbols) and the
/// Laplace approximation ((p - p_opt) / stderr_statistical)^2 (line).
pub fn likelihood(r: &CalibrationReport, png: &Path) -> anyhow::Result<PathBuf> {
    register_font()?;
    let n = r.fitted.len().max(1);
    let root = BitMapBackend::new(png, (420 * n as u32 + 20, 440)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled("profile likelihoods", ("sans-serif", 20))?;
    for (f, area) in r.fitted.iter().zip(root.split_evenly((1, n))) {
        let pts: Vec<(f64, f64)> =
            f.profile.iter().filter(|p| p.delta_chi2.is_finite()).map(|p| (p.value, p.delta_chi2)).collect();
        let (x0, x1) = pts.iter().fold((f.value, f.value), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (x0, x1) = if x1 > x0 { (x0, x1) } else { (f.value - 1.0, f.value + 1.0) };
        let sigma = f.stderr_statistical;
        let laplace = |x: f64| if sigma > 0.0 { ((x - f.value) / sigma).powi(2) } else { f64::NAN };
        let ymax = pts
            .iter()
            .map(|p| p.1)
            .chain((0..=40).map(|i| laplace(x0 + (x1 - x0) * i as f64 / 40.0)))
            .filter(|v| v.is_finite())
            .fold(1.0f64, f64::max)
            * 1.1;
        let mut chart = ChartBuilder::on(&area)
            .caption(&f.key, ("sans-serif", 15))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, 0.0..ymax)?;
        chart.configure_mesh().x_desc("value").y_desc("chi2 - chi2_min").label_style(("sans-serif", 13)).draw()?;
        if sigma > 0.0 {
            let line =
                (0..=80).map(|i| x0 + (x1 - x0) * i as f64 / 80.0).map(|x| (x, laplace(x))).filter(|p| p.1 <= ymax);
            chart
                .draw_series(LineSeries::new(line, COLORS[0].stroke_width(2)))?
                .label("Laplace approximation")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], COLORS[0].stroke_width(2)));
        }
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, COLORS[1].filled())))?
            .label("others refitted")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, COLORS[1].filled()));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperMiddle)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()?;
    }
    root.present()?;
    Ok(png.to_path_buf())
}
