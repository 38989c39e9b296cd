//! Figures of a run's phase averages (`output.phases`): `phases.png`, the phase-averaged
//! transport rate over one period with its standard error over the periods and the
//! forcing signal beside it, and `phase_profiles.png`, the profiles of phi, u_p and u_f at
//! four phases (the bins nearest t/T = 0, 1/4, 1/2 and 3/4) over the heights where the
//! grains move. Drawn from the files the run wrote ([`saltus_solvers::run::phases`]), so
//! that a finished or interrupted run draws the same figures.

use std::path::{Path, PathBuf};

use std::ops::DerefMut;

use anyhow::{bail, Context};
use plotters::prelude::*;
use saltus_solvers::run::phases::{PHASES, PHASE_PROFILES};

use super::profiles::{self, Columns, Panel, PHI_PANEL, U_P_PANEL};
use super::{canvas, color, error_bars, legend, line_key, PAGE};
use crate::table::Table;

/// File of the transport-rate figure.
pub const QS_FIGURE: &str = "phases.png";
/// File of the phase-profile figure.
pub const PROFILE_FIGURE: &str = "phase_profiles.png";

/// Phases drawn in [`PROFILE_FIGURE`], as fractions of the period.
const SHOWN: [f64; 4] = [0.0, 0.25, 0.5, 0.75];

const PROFILE_PANELS: [Panel; 3] = [
    PHI_PANEL,
    U_P_PANEL,
    Panel {
        title: "fluid velocity",
        x_desc: "u_f [m/s]",
        columns: &["u_f"],
        log_x: false,
        legend: SeriesLabelPosition::UpperLeft,
    },
];

/// Draw the phase figures of the run in `out` under `title`; nothing (an empty list) when
/// the run wrote no phase averages (no periodic forcing, or no whole period averaged).
pub fn draw(out: &Path, title: &str) -> anyhow::Result<Vec<PathBuf>> {
    let qs_file = out.join(PHASES);
    if !qs_file.is_file() {
        return Ok(Vec::new());
    }
    let qs = Table::read_profiles_file(&qs_file)?;
    if qs.rows() == 0 {
        return Ok(Vec::new());
    }
    let mut written = Vec::new();
    let png = out.join(QS_FIGURE);
    draw_qs(&qs, title, &png).with_context(|| format!("{}: cannot draw", png.display()))?;
    written.push(png);
    let profiles_file = out.join(PHASE_PROFILES);
    if profiles_file.is_file() {
        let bins = split_bins(&Table::read_profiles_file(&profiles_file)?)
            .with_context(|| format!("{}: cannot read the phase bins", profiles_file.display()))?;
        let png = out.join(PROFILE_FIGURE);
        draw_bins(&bins, title, &png).with_context(|| format!("{}: cannot draw", png.display()))?;
        written.push(png);
    }
    Ok(written)
}

/// One phase bin's profiles: its phase t/T and its columns.
struct Bin {
    phase: f64,
    table: Table,
}

/// The blocks of rows of `phase_profiles.csv`, one per bin.
fn split_bins(t: &Table) -> anyhow::Result<Vec<Bin>> {
    let (Some(bin), Some(phase)) = (t.get("phase"), t.get("t_over_period")) else {
        bail!("the columns `phase` and `t_over_period` are missing");
    };
    let mut bins: Vec<Bin> = Vec::new();
    for row in 0..t.rows() {
        if row == 0 || bin[row] != bin[row - 1] {
            let mut table = Table::default();
            for name in &t.names {
                table.push(name.clone(), Vec::new());
            }
            bins.push(Bin { phase: phase[row], table });
        }
        let Some(b) = bins.last_mut() else { bail!("no bin") };
        for (c, col) in b.table.columns.iter_mut().zip(&t.columns) {
            c.push(col[row]);
        }
    }
    Ok(bins)
}

/// Heights drawn in the profile figure: from one sheet thickness h below the lowest level
/// where phi first falls below 0.9 of its largest value (the top of the bed at rest) to
/// four above the highest level the grains reach (phi above 1e-3), within the column: the
/// eroded bed, the sheet and the lower part of the wave boundary layer above it; `None` when the bins show
/// no such sheet (then the whole column is drawn).
fn sheet_window(bins: &[Bin]) -> Option<(f64, f64)> {
    let (mut bed, mut top) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for b in bins {
        let (z, phi) = (b.table.get("z")?, b.table.get("phi")?);
        let max = phi.iter().copied().filter(|p| p.is_finite()).fold(0.0, f64::max);
        if max <= 0.0 {
            return None;
        }
        let loosened = z.iter().zip(phi).find(|(_, p)| **p < 0.9 * max).map(|(z, _)| *z)?;
        let reached = z.iter().zip(phi).filter(|(_, p)| **p > 1e-3).map(|(z, _)| *z).fold(f64::NEG_INFINITY, f64::max);
        bed = bed.min(loosened);
        top = top.max(reached);
        lo = z.iter().copied().fold(lo, f64::min);
        hi = z.iter().copied().fold(hi, f64::max);
    }
    let h = top - bed;
    (h > 0.0 && h.is_finite()).then(|| ((bed - h).max(lo), (top + 4.0 * h).min(hi)))
}

fn draw_bins(bins: &[Bin], title: &str, png: &Path) -> anyhow::Result<()> {
    if bins.is_empty() {
        bail!("no phase bin");
    }
    let mut chosen: Vec<usize> = Vec::new();
    for target in SHOWN {
        // the bin nearest the phase, on the circle
        let distance = |b: &Bin| {
            let d = (b.phase - target).rem_euclid(1.0);
            d.min(1.0 - d)
        };
        let nearest = (0..bins.len()).min_by(|&i, &j| distance(&bins[i]).total_cmp(&distance(&bins[j])));
        if let Some(i) = nearest.filter(|i| !chosen.contains(i)) {
            chosen.push(i);
        }
    }
    let curves: Vec<(String, &dyn Columns)> =
        chosen.iter().map(|&i| (format!("t/T = {:.3}", bins[i].phase), &bins[i].table as &dyn Columns)).collect();
    let caption = format!("{title}: phase-averaged profiles");
    profiles::draw_columns(&caption, &PROFILE_PANELS, &curves, &[], sheet_window(bins), png)
}

fn draw_qs(t: &Table, title: &str, png: &Path) -> anyhow::Result<()> {
    let (Some(phase), Some(qs), Some(err), Some(forcing)) =
        (t.get("t_over_period"), t.get("qs"), t.get("qs_error"), t.get("forcing"))
    else {
        bail!("the columns t_over_period, qs, qs_error and forcing are missing");
    };
    let finite = |v: f64| v.is_finite();
    let band = |lo: f64, hi: f64| {
        let pad = 0.08 * (hi - lo).max(lo.abs().max(hi.abs()) * 1e-3).max(1e-300);
        (lo - pad, hi + pad)
    };
    let (mut q0, mut q1) = (0.0f64, 0.0f64);
    for (q, e) in qs.iter().zip(err) {
        if finite(*q) {
            let e = if finite(*e) { *e } else { 0.0 };
            q0 = q0.min(q - e);
            q1 = q1.max(q + e);
        }
    }
    let (q0, q1) = band(q0, q1);
    let (f0, f1) =
        forcing.iter().copied().filter(|f| f.is_finite()).fold((0.0f64, 0.0f64), |(a, b), f| (a.min(f), b.max(f)));
    let (f0, f1) = band(f0, f1);
    let root = canvas(png, (900, 560))?;
    let mut chart = PAGE
        .on(&root, &format!("{title}: transport rate over a period"))
        .y_label_area_size(80)
        .right_y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, q0..q1)?
        .set_secondary_coord(0.0..1.0, f0..f1);
    chart
        .configure_mesh()
        .x_desc("t / T")
        .y_desc("q_s [m^2/s]")
        .y_label_formatter(&|y| format!("{y:.1e}"))
        .label_style(("sans-serif", 15))
        .draw()?;
    chart.configure_secondary_axes().y_desc("forcing").label_style(("sans-serif", 15)).draw()?;
    let (qc, fc) = (color(0), color(1));
    let points: Vec<(f64, f64, f64)> = phase
        .iter()
        .zip(qs)
        .zip(err)
        .filter(|((p, q), _)| finite(**p) && finite(**q))
        .map(|((&p, &q), &e)| (p, q, if finite(e) { e } else { 0.0 }))
        .collect();
    chart
        .draw_series(LineSeries::new(points.iter().map(|&(p, q, _)| (p, q)), qc.stroke_width(2)))?
        .label("q_s, phase average")
        .legend(line_key(qc, 2));
    chart.draw_series(error_bars(points.iter().copied(), (q0, q1), qc.stroke_width(1)))?;
    chart
        .draw_secondary_series(LineSeries::new(
            phase.iter().zip(forcing).filter(|(p, f)| finite(**p) && finite(**f)).map(|(&p, &f)| (p, f)),
            fc.stroke_width(1),
        ))?
        .label("forcing (right axis)")
        .legend(line_key(fc, 1));
    legend(chart.deref_mut(), SeriesLabelPosition::UpperRight, 14)?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bin_table(rows: &[(f64, f64, f64, f64)]) -> Table {
        let mut t = Table::default();
        for (k, name) in ["phase", "t_over_period", "z", "phi"].iter().enumerate() {
            t.push(*name, rows.iter().map(|r| [r.0, r.1, r.2, r.3][k]).collect());
        }
        t
    }

    #[test]
    fn bins_are_the_blocks_of_rows_of_one_phase() {
        let t =
            bin_table(&[(0.0, 0.25, 0.1, 0.6), (0.0, 0.25, 0.2, 0.0), (1.0, 0.75, 0.1, 0.5), (1.0, 0.75, 0.2, 0.1)]);
        let bins = split_bins(&t).expect("bins");
        assert_eq!(bins.len(), 2);
        assert_eq!((bins[0].phase, bins[1].phase), (0.25, 0.75));
        assert_eq!(bins[1].table.get("phi"), Some(&[0.5, 0.1][..]));
    }

    #[test]
    fn the_window_spans_the_sheet_and_stays_in_the_column() {
        // a bed of phi 0.6 to z = 1, a sheet thinning to nothing at z = 2
        let z: Vec<f64> = (0..40).map(|i| 0.05 + 0.1 * f64::from(i)).collect();
        let rows: Vec<(f64, f64, f64, f64)> =
            z.iter().map(|&z| (0.0, 0.0, z, if z < 1.0 { 0.6 } else { (0.6 * (2.0 - z)).max(0.0) })).collect();
        let bins = split_bins(&bin_table(&rows)).expect("bins");
        let (lo, hi) = sheet_window(&bins).expect("window");
        // below 0.9 of 0.6 first at z = 1.15, grains up to z = 1.95: h = 0.8, and the top
        // clipped to the column's highest centre
        assert!((lo - 0.35).abs() < 1e-9 && (hi - 3.95).abs() < 1e-9, "{lo} {hi}");
        // no grains: no window
        let clear: Vec<_> = z.iter().map(|&z| (0.0, 0.0, z, 0.0)).collect();
        assert!(sheet_window(&split_bins(&bin_table(&clear)).expect("bins")).is_none());
    }
}
