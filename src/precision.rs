//! Work against precision of the variants of a comparison: each variant's error against a
//! reference (another variant, typically the most resolved, or the base scene's reference
//! data and a published transport rate) beside its cost, as `precision.csv` and a log-log
//! figure `precision.png`.
//!
//! Errors, per variant:
//! * `qs_star_error`: (qs* - qs*_ref) / qs*_ref, signed;
//! * `qs_star_error_bar`: the statistical error of that difference, sqrt(se^2 + se_ref^2) /
//!   |qs*_ref| with se the DEM runs' standard errors of qs* (0 for the Eulerian solver's
//!   deterministic runs), so that a difference inside its bar is not resolved;
//! * `rms_phi`, `rms_u_p`, `rms_u_f`: the RMS difference of the profile from the
//!   reference's (the run interpolated in z onto the reference's rows, see
//!   [`crate::differences`]) over the largest |value| of the reference profile;
//! * `moving_rms_phi`, `moving_rms_u_p`: the RMS differences of phi and u_p, in their
//!   units, over the reference's rows where the grains move (phi above [`MOVING_PHI`] and
//!   u_p above [`MOVING_U_P`] times the largest u_p where phi is): the layer that carries the transport,
//!   without the clear fluid above it and the creeping bed below. Against a DEM run as the
//!   reference, a second seed of that run (a variant with another `seed`) gives the
//!   seed-to-seed scatter in the same measure: for a continuum variant, an RMS no larger
//!   than the second seed's means a bias no larger than one seed's standard deviation
//!   (E[(m - s1)^2] = b^2 + sd^2 against E[(s2 - s1)^2] = 2 sd^2).
//!
//!   With `smooth = H` every profile of this measure (the reference's and the run's) is
//!   first weighted with the Gaussian of Fry et al. 2024 eq 11, exp(-((z - z')/h_g)^2)
//!   normalised over the column, of h_g = H grain diameters: phi and the flux phi u_p are
//!   smoothed, u_p is their ratio. A DEM bed in a small cell stacks its grains in layers
//!   about a diameter apart, which no continuum closure has a term for; Fry et al. average
//!   their DEM fields so before fitting the closures. With `align = true` each profile is
//!   taken against the distance above its own bed surface, the level below which 1 % of its
//!   flux flows, rather than at the same height, so that a bed standing higher or lower
//!   (a looser deposit) is not counted as a difference of the moving layer.
//!
//! The cost is the run's CPU time (summary `cpu_time_s`), else its wall time.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Context;
use plotters::prelude::*;
use saltus_solvers::{Profiles, RunReport};
use serde::Deserialize;

use crate::differences;
use crate::plot::register_font;
use crate::table::Table;

/// File names written beside the comparison table.
pub const TABLE: &str = "precision.csv";
/// See [`TABLE`].
pub const FIGURE: &str = "precision.png";

/// Profile columns whose relative RMS difference the table gives.
pub const PROFILES: [&str; 3] = ["phi", "u_p", "u_f"];

/// Profile columns whose RMS difference over the moving layer the table gives.
pub const MOVING: [&str; 2] = ["phi", "u_p"];

/// Rows of the reference where the grains move: phi above this (no clear fluid, where a
/// DEM's u_p is undefined)...
pub const MOVING_PHI: f64 = 0.01;

/// ...and u_p above this fraction of the largest u_p of those rows (no creeping bed).
pub const MOVING_U_P: f64 = 0.05;

/// The `[reference]` table of a compare file.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// the variant every other is measured against
    #[serde(default)]
    pub variant: Option<String>,
    /// measure the profiles against the base scene's reference data
    #[serde(default)]
    pub data: bool,
    /// a published qs* to measure the rates against (with `data`, or alone)
    #[serde(default)]
    pub qs_star: Option<f64>,
    /// its standard error
    #[serde(default)]
    pub qs_star_stderr: Option<f64>,
    /// h_g of Fry et al. 2024's eq-11 Gaussian, in grain diameters, applied to the profiles
    /// of the moving-layer RMS (with a reference `variant`)
    #[serde(default)]
    pub smooth: Option<f64>,
    /// the moving-layer RMS against the distance above each profile's bed surface (with a
    /// reference `variant`)
    #[serde(default)]
    pub align: bool,
}

/// Largest `smooth` (grain diameters): beyond it the Gaussian spans any bed of the scenes.
pub const MAX_SMOOTH: f64 = 100.0;

/// Reach of the smoothing Gaussian, in h_g: exp(-5^2) = 1.4e-11.
const GAUSS_REACH: f64 = 5.0;

/// Fraction of a profile's flux that flows below its bed surface (`align`).
pub const BED_FLUX: f64 = 0.01;

/// One row of the table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Row {
    /// variant name
    pub variant: String,
    /// CPU time of the run (s), when the summary has it
    pub cpu_time_s: Option<f64>,
    /// wall time of the run (s)
    pub wall_time_s: Option<f64>,
    /// the run's qs*
    pub qs_star: Option<f64>,
    /// its standard error (DEM runs)
    pub qs_star_stderr: Option<f64>,
    /// relative error of qs*, signed
    pub qs_star_error: Option<f64>,
    /// statistical error of that relative difference
    pub qs_star_error_bar: Option<f64>,
    /// relative RMS differences of [`PROFILES`], in that order
    pub rms: [Option<f64>; 3],
    /// RMS differences of [`MOVING`] over the reference's moving layer, in their units
    pub moving_rms: [Option<f64>; 2],
}

impl Row {
    /// The cost: CPU time, else wall time.
    pub fn cost(&self) -> Option<f64> {
        self.cpu_time_s.or(self.wall_time_s)
    }
}

/// Header of `precision.csv`.
pub fn header() -> Vec<String> {
    let mut h: Vec<String> =
        ["variant", "cpu_time_s", "wall_time_s", "qs_star", "qs_star_stderr", "qs_star_error", "qs_star_error_bar"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    h.extend(PROFILES.iter().map(|c| format!("rms_{c}")));
    h.extend(MOVING.iter().map(|c| format!("moving_rms_{c}")));
    h
}

/// The rows: every variant against the reference (the reference variant itself included,
/// with zero errors). `runs` are (name, report) in file order; `data` the base scene's
/// reference tables; `diameter` the grain diameter (m) that `smooth` counts in.
pub fn rows(spec: &ReferenceSpec, runs: &[(&str, Option<&RunReport>)], data: &[&Table], diameter: f64) -> Vec<Row> {
    let reference = spec.variant.as_deref().and_then(|v| runs.iter().find(|(n, _)| *n == v)).and_then(|(_, r)| *r);
    let (q_ref, se_ref) = match reference {
        Some(r) => (r.summary.qs_star, r.summary.qs_star_stderr.unwrap_or(0.0)),
        None => (spec.qs_star, spec.qs_star_stderr.unwrap_or(0.0)),
    };
    let own = reference.map(|r| to_table(&r.profiles));
    let profiles_ref: Vec<&Table> = match &own {
        Some(t) => vec![t],
        None if spec.data => data.to_vec(),
        None => Vec::new(),
    };
    let h_g = spec.smooth.unwrap_or(0.0) * diameter;
    let prepare = |p: &Profiles| {
        if h_g > 0.0 || spec.align {
            moving_profiles(p, h_g, spec.align)
        } else {
            Some(p.clone())
        }
    };
    // smoothing and alignment apply to a reference run, whose profiles are on its own cells
    let moving_ref = match (reference, h_g > 0.0 || spec.align) {
        (Some(r), true) => prepare(&r.profiles).and_then(|p| moving_layer(&to_table(&p))),
        _ => profiles_ref.iter().find_map(|t| moving_layer(t)),
    };
    runs.iter()
        .map(|(name, report)| {
            let mut row = Row { variant: name.to_string(), ..Row::default() };
            let Some(rep) = report else { return row };
            let s = &rep.summary;
            row.cpu_time_s = s.cpu_time_s;
            row.wall_time_s = Some(s.wall_time_s);
            row.qs_star = s.qs_star;
            row.qs_star_stderr = s.qs_star_stderr;
            if let (Some(q), Some(q0)) = (s.qs_star, q_ref.filter(|q| *q != 0.0)) {
                row.qs_star_error = Some((q - q0) / q0);
                let se = s.qs_star_stderr.unwrap_or(0.0);
                row.qs_star_error_bar = Some((se * se + se_ref * se_ref).sqrt() / q0.abs());
            }
            for (k, c) in PROFILES.iter().enumerate() {
                row.rms[k] = profiles_ref.iter().find_map(|t| relative_rms(&rep.profiles, t, c));
            }
            if let (Some(m), Some(p)) = (&moving_ref, prepare(&rep.profiles)) {
                for (k, c) in MOVING.iter().enumerate() {
                    row.moving_rms[k] = differences::rms_difference(&p, m, c).map(|(r, _)| r);
                }
            }
            row
        })
        .collect()
}

/// RMS difference of `column` over the largest |value| of the reference's column.
fn relative_rms(run: &Profiles, reference: &Table, column: &str) -> Option<f64> {
    let scale = reference.get(column)?.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let (rms, _) = differences::rms_difference(run, reference, column)?;
    (scale > 0.0).then(|| rms / scale)
}

/// The rows of `reference` where the grains move ([`MOVING_PHI`], [`MOVING_U_P`]), with its
/// z, phi and u_p; `None` without those columns or without such a row.
fn moving_layer(reference: &Table) -> Option<Table> {
    let (z, phi, u_p) = (reference.get("z")?, reference.get("phi")?, reference.get("u_p")?);
    // the largest u_p among the grains: an Eulerian reference's u_p is defined in the clear
    // fluid too, where it can exceed the layer's
    let top = (0..z.len()).filter(|&k| phi[k] > MOVING_PHI && u_p[k].is_finite()).fold(0.0f64, |m, k| m.max(u_p[k]));
    let keep: Vec<usize> =
        (0..z.len()).filter(|&k| phi[k] > MOVING_PHI && u_p[k] > MOVING_U_P * top && top > 0.0).collect();
    if keep.is_empty() {
        return None;
    }
    let mut t = Table::default();
    for (name, col) in [("z", z), ("phi", phi), ("u_p", u_p)] {
        t.push(name, keep.iter().map(|&k| col[k]).collect());
    }
    Some(t)
}

/// z, phi and u_p of `p` for the moving-layer RMS: phi and the flux phi u_p weighted with
/// Fry et al. 2024's eq-11 Gaussian of width `h_g` (m; none when 0), normalised over the
/// column and by the cells' widths, u_p their ratio (the run's own where no grain is); z taken from the
/// bed surface (the level below which [`BED_FLUX`] of the flux flows) when `align`. `None`
/// without z, phi and u_p, or, when aligned, without a flux.
fn moving_profiles(p: &Profiles, h_g: f64, align: bool) -> Option<Profiles> {
    let (z, phi, u_p) = (p.get("z")?, p.get("phi")?, p.get("u_p")?);
    let n = z.len();
    if n == 0 || phi.len() != n || u_p.len() != n {
        return None;
    }
    let finite = |v: f64| if v.is_finite() { v } else { 0.0 };
    let dz = cell_widths(z);
    let mut phi_s: Vec<f64> = phi.iter().map(|&v| finite(v)).collect();
    let mut flux: Vec<f64> = (0..n).map(|k| phi_s[k] * finite(u_p[k])).collect();
    if h_g > 0.0 {
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        // beyond GAUSS_REACH h_g a weight is below 1e-10 of the centre's: the sum over the
        // cells within reach keeps a column of many cells linear in its length
        let sorted = z.windows(2).all(|w| w[0] <= w[1]);
        for k in 0..n {
            let (lo, hi) = if sorted {
                (
                    z.partition_point(|&v| v < z[k] - GAUSS_REACH * h_g),
                    z.partition_point(|&v| v <= z[k] + GAUSS_REACH * h_g),
                )
            } else {
                (0, n)
            };
            let (mut w_sum, mut pa, mut fb) = (0.0, 0.0, 0.0);
            for j in lo..hi {
                let w = (-((z[k] - z[j]) / h_g).powi(2)).exp() * dz[j];
                w_sum += w;
                pa += w * phi_s[j];
                fb += w * flux[j];
            }
            if w_sum > 0.0 {
                a[k] = pa / w_sum;
                b[k] = fb / w_sum;
            }
        }
        phi_s = a;
        flux = b;
    }
    // where no grain is (after smoothing), the run's own u_p: a continuum's is defined there
    let u: Vec<f64> = (0..n).map(|k| if phi_s[k] > 1e-9 { flux[k] / phi_s[k] } else { finite(u_p[k]) }).collect();
    let shift = if align { bed_surface(z, &dz, &flux)? } else { 0.0 };
    let mut out = Profiles::default();
    out.push("z", z.iter().map(|v| v - shift).collect());
    out.push("phi", phi_s);
    out.push("u_p", u);
    Some(out)
}

/// Widths of the cells whose centres are `z` (each half the distance to its neighbours on
/// either side; the end cells mirror their one neighbour).
fn cell_widths(z: &[f64]) -> Vec<f64> {
    let n = z.len();
    (0..n)
        .map(|k| match (k.checked_sub(1).map(|i| z[i]), z.get(k + 1)) {
            (Some(lo), Some(hi)) => 0.5 * (hi - lo),
            (None, Some(hi)) => hi - z[k],
            (Some(lo), None) => z[k] - lo,
            (None, None) => 0.0,
        })
        .map(|w| if w.is_finite() && w > 0.0 { w } else { 0.0 })
        .collect()
}

/// The level below which [`BED_FLUX`] of the (positive) flux flows, linear between the
/// cells' top faces; `None` without a positive flux.
fn bed_surface(z: &[f64], dz: &[f64], flux: &[f64]) -> Option<f64> {
    let total: f64 = flux.iter().zip(dz).map(|(f, w)| f.max(0.0) * w).sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let target = BED_FLUX * total;
    let (mut below, mut face) = (0.0, z[0] - 0.5 * dz[0]);
    for k in 0..z.len() {
        let add = flux[k].max(0.0) * dz[k];
        let top = z[k] + 0.5 * dz[k];
        if below + add >= target {
            return Some(face + (top - face) * (target - below) / add);
        }
        below += add;
        face = top;
    }
    Some(face)
}

fn to_table(p: &Profiles) -> Table {
    let mut t = Table::default();
    for (name, values) in &p.columns {
        t.push(name.clone(), values.clone());
    }
    t
}

fn cell(v: Option<f64>, precise: bool) -> String {
    match (v, precise) {
        (None, _) => String::new(),
        (Some(v), true) => format!("{v:?}"),
        (Some(v), false) => format!("{v:.4}"),
    }
}

/// The cells of one row, `precise` with every digit (the CSV), else rounded.
pub fn cells(r: &Row, precise: bool) -> Vec<String> {
    let mut c = vec![r.variant.clone()];
    for v in [r.cpu_time_s, r.wall_time_s, r.qs_star, r.qs_star_stderr, r.qs_star_error, r.qs_star_error_bar] {
        c.push(cell(v, precise));
    }
    c.extend(r.rms.iter().map(|v| cell(*v, precise)));
    c.extend(r.moving_rms.iter().map(|v| cell(*v, precise)));
    c
}

/// Write `precision.csv` into `out`.
pub fn write(rows: &[Row], out: &Path) -> anyhow::Result<std::path::PathBuf> {
    let path = out.join(TABLE);
    let mut w = csv::Writer::from_path(&path).with_context(|| format!("{}: cannot create", path.display()))?;
    w.write_record(header())?;
    for r in rows {
        w.write_record(cells(r, true))?;
    }
    w.flush().with_context(|| format!("{}: cannot write", path.display()))?;
    Ok(path)
}

/// The table as text lines, for the terminal.
pub fn text(rows: &[Row]) -> String {
    let mut s = String::new();
    let header = header();
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| cells(r, false).into_iter().map(|c| if c.is_empty() { "-".into() } else { c }).collect())
        .collect();
    let width: Vec<usize> = (0..header.len())
        .map(|k| body.iter().map(|r| r[k].len()).chain([header[k].len()]).max().unwrap_or(0))
        .collect();
    for row in std::iter::once(&header).chain(&body) {
        let line: Vec<String> = row
            .iter()
            .enumerate()
            .map(|(k, c)| if k == 0 { format!("{c:<w$}", w = width[k]) } else { format!("{c:>w$}", w = width[k]) })
            .collect();
        let _ = writeln!(s, "{}", line.join("  ").trim_end());
    }
    s
}

/// One drawn error of a row.
type Measure = fn(&Row) -> Option<f64>;

/// Draw |qs* error| against cost on log-log axes, with the statistical bars, and the
/// profile errors (RMS phi, u_p) beside them; rows without a positive cost and error are
/// left out. Returns `Ok(false)` when no row can be drawn.
pub fn draw(title: &str, rows: &[Row], png: &Path) -> anyhow::Result<bool> {
    let series: [(&str, Measure); 3] = [
        ("|qs* error|", |r| r.qs_star_error.map(f64::abs)),
        ("RMS phi / max phi", |r| r.rms[0]),
        ("RMS u_p / max u_p", |r| r.rms[1]),
    ];
    let marks: Vec<(usize, f64, f64, &Row)> = series
        .iter()
        .enumerate()
        .flat_map(|(k, (_, f))| {
            rows.iter().filter_map(move |r| {
                let (x, y) = (r.cost()?, f(r)?);
                (x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite()).then_some((k, x, y, r))
            })
        })
        .collect();
    if marks.is_empty() {
        return Ok(false);
    }
    register_font()?;
    let bars = rows.iter().filter_map(|r| r.qs_star_error_bar.filter(|b| *b > 0.0));
    let (x0, x1) = marks.iter().fold((f64::INFINITY, 0.0f64), |(a, b), m| (a.min(m.1), b.max(m.1)));
    let (y0, y1) =
        marks.iter().map(|m| m.2).chain(bars).fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    let (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 2.0, y1 * 2.0);
    let root = BitMapBackend::new(png, (900, 680)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    let x_desc = if rows.iter().all(|r| r.cpu_time_s.is_some()) { "CPU time (s)" } else { "CPU (or wall) time (s)" };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("error against the reference")
        .label_style(("sans-serif", 15))
        .draw()?;
    let colors = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44)];
    for (k, (label, _)) in series.iter().enumerate() {
        let color = colors[k];
        let mine: Vec<_> = marks.iter().filter(|m| m.0 == k).collect();
        if mine.is_empty() {
            continue;
        }
        if k == 0 {
            // the statistical bar: a difference inside it is not resolved
            for m in &mine {
                if let Some(b) = m.3.qs_star_error_bar.filter(|b| *b > 0.0) {
                    let (lo, hi) = ((m.2 - b).max(y0), (m.2 + b).min(y1));
                    chart.draw_series(LineSeries::new([(m.1, lo), (m.1, hi)], color.stroke_width(1)))?;
                }
            }
            chart.draw_series(mine.iter().map(|m| {
                Text::new(format!(" {}", m.3.variant), (m.1, m.2), ("sans-serif", 12).into_font().color(&BLACK))
            }))?;
        }
        chart
            .draw_series(mine.iter().map(|m| Circle::new((m.1, m.2), 4, color.filled())))?
            .label(*label)
            .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    root.present().with_context(|| format!("{}: cannot write", png.display()))?;
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use saltus_solvers::Summary;

    fn report(qs_star: f64, se: Option<f64>, cpu: f64, phi: Vec<f64>) -> RunReport {
        let mut profiles = Profiles::default();
        profiles.push("z", vec![0.0, 1.0, 2.0]);
        profiles.push("phi", phi);
        let summary = Summary {
            qs_star: Some(qs_star),
            qs_star_stderr: se,
            cpu_time_s: Some(cpu),
            wall_time_s: 2.0 * cpu,
            ..Summary::default()
        };
        RunReport { summary, profiles, text: String::new() }
    }

    #[test]
    fn errors_against_a_reference_variant() {
        let fine = report(2.0, Some(0.03), 100.0, vec![0.6, 0.3, 0.0]);
        let coarse = report(2.1, Some(0.04), 10.0, vec![0.6, 0.36, 0.0]);
        let spec = ReferenceSpec { variant: Some("fine".into()), ..ReferenceSpec::default() };
        let rows = rows(&spec, &[("coarse", Some(&coarse)), ("fine", Some(&fine)), ("failed", None)], &[], 1.0);
        let c = &rows[0];
        assert!((c.qs_star_error.unwrap() - 0.05).abs() < 1e-15);
        // sqrt(0.03^2 + 0.04^2) / 2 = 0.025
        assert!((c.qs_star_error_bar.unwrap() - 0.025).abs() < 1e-15);
        // one row of three differs by 0.06: RMS 0.06 / sqrt(3) over max phi 0.6
        assert!((c.rms[0].unwrap() - 0.06 / 3f64.sqrt() / 0.6).abs() < 1e-12);
        assert_eq!(c.cost(), Some(10.0));
        // the reference against itself
        assert_eq!(rows[1].qs_star_error, Some(0.0));
        assert_eq!(rows[1].rms[0], Some(0.0));
        // a variant without a run has an empty row
        assert_eq!(rows[2], Row { variant: "failed".into(), ..Row::default() });
    }

    /// The moving-layer RMS sees only the rows where the reference's grains move: a run
    /// that differs in the clear fluid (phi <= 0.01) and in the creeping bed (u_p <= 5 %
    /// of the largest) has none, one that differs inside the layer has its difference.
    #[test]
    fn the_moving_layer_leaves_out_the_clear_fluid_and_the_creeping_bed() {
        let profiles = |phi: Vec<f64>, u_p: Vec<f64>| {
            let mut p = Profiles::default();
            p.push("z", vec![0.0, 1.0, 2.0, 3.0, 4.0]);
            p.push("phi", phi);
            p.push("u_p", u_p);
            RunReport {
                summary: Summary { qs_star: Some(1.0), ..Summary::default() },
                profiles: p,
                text: String::new(),
            }
        };
        // bed (creeping), two moving rows, clear fluid
        let dem = profiles(vec![0.6, 0.6, 0.4, 0.1, 0.0], vec![0.001, 0.04, 0.5, 1.0, 2.0]);
        let outside = profiles(vec![0.55, 0.6, 0.4, 0.1, 0.05], vec![0.03, 0.04, 0.5, 1.0, 0.0]);
        let inside = profiles(vec![0.6, 0.6, 0.43, 0.1, 0.0], vec![0.001, 0.04, 0.5, 0.9, 2.0]);
        let spec = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let rows =
            rows(&spec, &[("dem", Some(&dem)), ("outside", Some(&outside)), ("inside", Some(&inside))], &[], 1.0);
        // the largest u_p among the grains is 1.0 (the clear fluid's 2.0 is not counted):
        // rows 2 and 3 move, row 1 (0.04) creeps
        assert_eq!(rows[0].moving_rms, [Some(0.0), Some(0.0)]);
        assert!(rows[1].rms[0].unwrap() > 0.0 && rows[1].rms[1].unwrap() > 0.0, "{:?}", rows[1]);
        assert_eq!(rows[1].moving_rms, [Some(0.0), Some(0.0)]);
        // rows 2 and 3 move: differences 0.03 and 0 in phi, 0 and 0.1 in u_p
        let m = rows[2].moving_rms;
        assert!((m[0].unwrap() - 0.03 / 2f64.sqrt()).abs() < 1e-12, "{m:?}");
        assert!((m[1].unwrap() - 0.1 / 2f64.sqrt()).abs() < 1e-12, "{m:?}");
    }

    #[test]
    fn errors_against_a_published_rate_and_the_data() {
        let run = report(1.5, None, 1.0, vec![0.6, 0.3, 0.0]);
        let mut data = Table::default();
        data.push("z", vec![0.5, 1.5]);
        data.push("phi", vec![0.45, 0.15]);
        let spec = ReferenceSpec { data: true, qs_star: Some(2.0), qs_star_stderr: Some(0.1), ..Default::default() };
        let rows = rows(&spec, &[("only", Some(&run))], &[&data], 1.0);
        assert!((rows[0].qs_star_error.unwrap() + 0.25).abs() < 1e-15);
        assert!((rows[0].qs_star_error_bar.unwrap() - 0.05).abs() < 1e-15);
        // the run interpolates to the data exactly (linear phi)
        assert!(rows[0].rms[0].unwrap() < 1e-15);
        assert_eq!(rows[0].rms[1], None);
    }

    /// Centres of `n` even cells over `height`.
    fn centres(n: usize, height: f64) -> Vec<f64> {
        (0..n).map(|k| (k as f64 + 0.5) * height / n as f64).collect()
    }

    fn column(z: &[f64], phi: Vec<f64>, u_p: Vec<f64>) -> RunReport {
        let mut p = Profiles::default();
        p.push("z", z.to_vec());
        p.push("phi", phi);
        p.push("u_p", u_p);
        RunReport { summary: Summary { qs_star: Some(1.0), ..Summary::default() }, profiles: p, text: String::new() }
    }

    /// Grains stacked in layers one diameter apart (phi 0.3 +- 0.1 sin(2 pi z / d) over the
    /// middle of the column, tapered to an even 0.3 towards its ends) against a continuum's
    /// even 0.3: the layers are the whole difference, RMS 0.1 / sqrt 2 where they are full. Fry's Gaussian
    /// of h_g = d damps a wave of length d by exp(-pi^2) = 5.2e-5, so with `smooth = 1` the
    /// difference all but vanishes (what is left comes from the taper).
    #[test]
    fn smoothing_over_a_diameter_takes_out_the_grain_layers() {
        let d = 1e-3;
        let n = 800;
        let z = centres(n, 20.0 * d);
        let taper = |z: f64| {
            let x = ((z / d - 4.0) / 4.0).clamp(0.0, 1.0).min(((16.0 - z / d) / 4.0).clamp(0.0, 1.0));
            (0.5 - 0.5 * (std::f64::consts::PI * x).cos()).powi(2)
        };
        let layered: Vec<f64> =
            z.iter().map(|&z| 0.3 + 0.1 * taper(z) * (2.0 * std::f64::consts::PI * z / d).sin()).collect();
        let dem = column(&z, layered, vec![1.0; n]);
        let even = column(&z, vec![0.3; n], vec![1.0; n]);
        let runs = [("dem", Some(&dem)), ("continuum", Some(&even))];
        let plain = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let raw = rows(&plain, &runs, &[], d)[1].moving_rms[0].unwrap();
        // the layers are full over 4 d of the 20 d, rise over 4 d on either side, and are
        // absent from the 4 d at each end
        assert!(raw > 0.03 && raw < 0.1 / 2f64.sqrt(), "{raw}");
        let smoothed = ReferenceSpec { smooth: Some(1.0), ..plain };
        let s = rows(&smoothed, &runs, &[], d)[1].moving_rms[0].unwrap();
        // the taper's own rise leaks a little through the Gaussian: below 1 % of the layers
        assert!(s < 1e-2 * raw, "{s} against {raw}");
        // the layers are not in u_p: its difference stays zero either way
        assert!(rows(&smoothed, &runs, &[], d)[1].moving_rms[1].unwrap() < 1e-12);
    }

    /// The same moving layer standing 0.7 d higher (a looser deposit): at the same height
    /// it differs by a large part of phi, against the distance above each bed surface it
    /// does not.
    #[test]
    fn aligned_profiles_do_not_count_a_higher_bed_as_a_difference() {
        let d = 1e-3;
        let n = 400;
        let z = centres(n, 20.0 * d);
        let layer = |shift: f64| {
            let phi: Vec<f64> = z.iter().map(|&z| 0.3 * (1.0 - ((z - 8.0 * d - shift) / d).tanh())).collect();
            let u: Vec<f64> = z.iter().map(|&z| 0.05 * (1.0 + ((z - 8.0 * d - shift) / d).tanh())).collect();
            column(&z, phi, u)
        };
        let (dem, higher) = (layer(0.0), layer(0.7 * d));
        let runs = [("dem", Some(&dem)), ("higher", Some(&higher))];
        let plain = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let at_height = rows(&plain, &runs, &[], d)[1].moving_rms;
        let aligned = ReferenceSpec { align: true, ..plain };
        let from_bed = rows(&aligned, &runs, &[], d)[1].moving_rms;
        assert!(at_height[0].unwrap() > 0.1, "{at_height:?}");
        // interpolation between cells of d/20 only
        assert!(from_bed[0].unwrap() < 1e-3 && from_bed[1].unwrap() < 1e-4, "{from_bed:?}");
    }

    /// An even flux over cells of 0.1: 1 % of it flows below 1 % of the column's height.
    #[test]
    fn the_bed_surface_is_where_one_percent_of_the_flux_flows_below() {
        let z: Vec<f64> = (0..10).map(|k| 0.05 + 0.1 * k as f64).collect();
        let dz = cell_widths(&z);
        assert!(dz.iter().all(|w| (w - 0.1).abs() < 1e-12), "{dz:?}");
        let level = bed_surface(&z, &dz, &[2.0; 10]).unwrap();
        assert!((level - 0.01).abs() < 1e-12, "{level}");
        // flux only in the top three cells: 1 % of it is 0.03 of the way into the eighth cell
        let mut f = [0.0; 10];
        f[7..].fill(1.0);
        assert!((bed_surface(&z, &dz, &f).unwrap() - 0.703).abs() < 1e-12);
        assert_eq!(bed_surface(&z, &dz, &[0.0; 10]), None);
        assert_eq!(bed_surface(&z, &dz, &[f64::NAN; 10]), None);
    }
}
