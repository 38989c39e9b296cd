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
//!   [`super::differences`]) over the largest |value| of the reference profile;
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
use saltus_solvers::{Profiles, RunReport};
use serde::Deserialize;

use super::differences;
use crate::figures;
use crate::table::Table;

mod moving;

pub(crate) use moving::{moving_rows, prepared};
pub use moving::{BED_FLUX, MAX_SMOOTH, MOVING, MOVING_PHI, MOVING_U_P};

/// Refuse a `reference.smooth` of the study file `path` that is not a width h_g in grain
/// diameters in (0, [`MAX_SMOOTH`]].
pub fn check_smooth(path: &std::path::Path, smooth: Option<f64>) -> anyhow::Result<()> {
    match smooth.filter(|h| !(h.is_finite() && *h > 0.0 && *h <= MAX_SMOOTH)) {
        Some(h) => Err(crate::study_file::key_error(
            path,
            "reference.smooth",
            format!("{h}: h_g in grain diameters, a finite number > 0 and <= {MAX_SMOOTH}"),
        )),
        None => Ok(()),
    }
}

/// File names written beside the comparison table.
pub const TABLE: &str = "precision.csv";
/// See [`TABLE`].
pub const FIGURE: &str = "precision.png";

/// Profile columns whose relative RMS difference the table gives.
pub const PROFILES: [&str; 3] = ["phi", "u_p", "u_f"];

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
    let prepare = |p| moving::shaped(p, h_g, spec.align);
    // smoothing and alignment apply to a reference run, whose profiles are on its own cells
    let moving_ref = match (reference, h_g > 0.0 || spec.align) {
        (Some(r), true) => prepare(&r.profiles).and_then(|p| moving::layer(&to_table(&p))),
        _ => profiles_ref.iter().find_map(|t| moving::layer(t)),
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
    let measures: Vec<figures::precision::Measure> = series
        .iter()
        .map(|&(label, f)| figures::precision::Measure {
            label,
            marks: rows
                .iter()
                .filter_map(|r| {
                    let (cost, error) = (r.cost()?, f(r)?);
                    let drawn = cost > 0.0 && error > 0.0 && cost.is_finite() && error.is_finite();
                    drawn.then_some(figures::precision::Mark {
                        cost,
                        error,
                        bar: r.qs_star_error_bar,
                        name: &r.variant,
                    })
                })
                .collect(),
        })
        .collect();
    if measures.iter().all(|m| m.marks.is_empty()) {
        return Ok(false);
    }
    let x_desc = if rows.iter().all(|r| r.cpu_time_s.is_some()) { "CPU time (s)" } else { "CPU (or wall) time (s)" };
    figures::precision::draw(title, x_desc, &measures, png)?;
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
}
