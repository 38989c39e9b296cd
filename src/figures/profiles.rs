//! Profiles against z: one panel per quantity (phi, velocities, granular temperature),
//! one curve per run or per source, and reference data as symbols.

use std::path::Path;

use anyhow::bail;
use plotters::prelude::*;
// the legend corner of a panel, for the panels that callers build
pub use plotters::prelude::SeriesLabelPosition;
use saltus_solvers::Profiles;

use super::{canvas, circle_key, color, legend, line_key, triangle_key, Area, PANEL};
use crate::table::Table;

/// One panel of a profile figure: some profile columns against z.
#[derive(Clone, Debug)]
pub struct Panel {
    /// caption above the panel
    pub title: &'static str,
    /// x-axis description
    pub x_desc: &'static str,
    /// profile columns drawn (reference columns of the same names are overlaid)
    pub columns: &'static [&'static str],
    /// logarithmic x axis
    pub log_x: bool,
    /// legend corner
    pub legend: SeriesLabelPosition,
}

/// The volume-fraction panel of the profile figures.
pub const PHI_PANEL: Panel = Panel {
    title: "volume fraction",
    x_desc: "phi [-]",
    columns: &["phi"],
    log_x: false,
    legend: SeriesLabelPosition::UpperRight,
};
/// The particle-velocity panel of the profile figures.
pub const U_P_PANEL: Panel = Panel {
    title: "particle velocity",
    x_desc: "u_p [m/s]",
    columns: &["u_p"],
    log_x: false,
    legend: SeriesLabelPosition::UpperLeft,
};
const THETA_PANEL: Panel = Panel {
    title: "granular temperature",
    x_desc: "theta_g [m^2/s^2]",
    columns: &["theta_g"],
    log_x: true,
    legend: SeriesLabelPosition::UpperLeft,
};

/// Panels of `profiles.png` (one run): phi; u_p and u_f; theta_g when present.
pub const RUN_PANELS: [Panel; 3] = [
    PHI_PANEL,
    Panel {
        title: "velocities",
        x_desc: "u [m/s]",
        columns: &["u_p", "u_f"],
        log_x: false,
        legend: SeriesLabelPosition::UpperLeft,
    },
    THETA_PANEL,
];

/// Panels of `comparison.png` (several runs): phi; u_p; theta_g when present.
pub const COMPARE_PANELS: [Panel; 3] = [PHI_PANEL, U_P_PANEL, THETA_PANEL];

/// Particle-phase columns are drawn only where phi >= this (where phi is known): above
/// the granular layer a particle velocity or temperature means nothing (the DEM reference
/// files hold zeros there).
pub const PARTICLE_PHI_MIN: f64 = 1e-3;

/// Particle-phase columns, masked by [`PARTICLE_PHI_MIN`].
const PARTICLE_COLUMNS: [&str; 3] = ["u_p", "theta_g", "w_p"];

/// Most reference symbols drawn per column (rows are thinned evenly beyond).
const MAX_MARKS: usize = 160;

/// Reference data of a profile figure: a legend label and named columns (one is `z`).
pub struct Reference<'a> {
    /// legend label
    pub label: &'a str,
    /// columns
    pub table: &'a Table,
}

/// Anything with named columns: a run's [`Profiles`] or a [`Table`] read from a file.
pub trait Columns {
    /// the column of that name, if any
    fn column(&self, name: &str) -> Option<&[f64]>;
}

impl Columns for Profiles {
    fn column(&self, name: &str) -> Option<&[f64]> {
        self.get(name)
    }
}

impl Columns for Table {
    fn column(&self, name: &str) -> Option<&[f64]> {
        self.get(name)
    }
}

/// (x, z) points of column `name` against `z`: finite, positive on a log axis, and for
/// particle-phase columns only where phi >= [`PARTICLE_PHI_MIN`].
fn points(c: &dyn Columns, name: &str, log_x: bool) -> Vec<(f64, f64)> {
    let (Some(x), Some(z)) = (c.column(name), c.column("z")) else {
        return Vec::new();
    };
    let phi = if PARTICLE_COLUMNS.contains(&name) { c.column("phi") } else { None };
    x.iter()
        .zip(z)
        .enumerate()
        .filter(|(i, (x, z))| {
            x.is_finite()
                && z.is_finite()
                && (!log_x || **x > 0.0)
                && match phi {
                    None => true,
                    Some(p) => p.get(*i).is_some_and(|p| *p >= PARTICLE_PHI_MIN),
                }
        })
        .map(|(_, (&x, &z))| (x, z))
        .collect()
}

struct Line {
    label: String,
    color: RGBColor,
    points: Vec<(f64, f64)>,
}

struct Marks {
    label: String,
    color: RGBColor,
    triangle: bool,
    points: Vec<(f64, f64)>,
}

fn axis_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() || !hi.is_finite() {
        return if log { (1e-6, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        // the bed holds temperatures many decades below the transport layer's
        let lo = lo.max(hi * 1e-8);
        if hi <= lo {
            return super::log_span(lo, lo, 10.0);
        }
        super::log_span(lo, hi, 1.5)
    } else {
        // keep zero in view: profiles start from a bed at rest
        let (lo, hi) = (lo.min(0.0), hi.max(0.0));
        if hi <= lo {
            return (lo - 1.0, lo + 1.0);
        }
        let (a, b) = super::linear_span(lo, hi, 0.05);
        (if lo < 0.0 { a } else { lo }, b)
    }
}

/// Draw `curves` (legend label, profiles) on the `panels` that any of them fills, with the
/// reference columns of the same names as symbols, into `png`. Panels whose columns no
/// curve has (theta_g of a local rheology) are left out.
pub fn draw_profiles(
    title: &str,
    panels: &[Panel],
    curves: &[(String, &Profiles)],
    references: &[Reference],
    png: &Path,
) -> anyhow::Result<()> {
    let curves: Vec<(String, &dyn Columns)> = curves.iter().map(|(l, c)| (l.clone(), *c as &dyn Columns)).collect();
    draw_columns(title, panels, &curves, references, None, png)
}

/// [`draw_profiles`] for any column source, over the heights `window` (m) when given,
/// else over every finite height of the curves.
pub fn draw_columns(
    title: &str,
    panels: &[Panel],
    curves: &[(String, &dyn Columns)],
    references: &[Reference],
    window: Option<(f64, f64)>,
    png: &Path,
) -> anyhow::Result<()> {
    let shown: Vec<&Panel> =
        panels.iter().filter(|p| curves.iter().any(|(_, c)| p.columns.iter().any(|k| c.column(k).is_some()))).collect();
    if shown.is_empty() {
        bail!("no profile column to draw");
    }
    let (z0, z1) = match window {
        Some((lo, hi)) if lo.is_finite() && hi.is_finite() && hi > lo => (lo, hi),
        _ => {
            let z = curves.iter().filter_map(|(_, c)| c.column("z")).flatten().copied().filter(|z| z.is_finite());
            let (lo, hi) = z.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| (a.min(z), b.max(z)));
            if !(lo.is_finite() && hi.is_finite()) {
                bail!("the profiles hold no finite z");
            }
            // one height (a comparison with one usable cell) is drawn in a window of its
            // own height about it (at least a millimetre)
            let pad = if hi > lo { 0.02 * (hi - lo) } else { (0.5 * hi.abs()).max(1e-3) };
            // no padding below a bottom at z = 0 (a `-0.0` label)
            (if lo >= 0.0 && hi > lo { 0.0 } else { lo - pad }, hi + pad)
        }
    };
    let width = (380 * shown.len() as u32 + 20).max(860);
    let root = canvas(png, (width, 680))?;
    let root = root.titled(title, ("sans-serif", 22))?;
    for (panel, area) in shown.iter().zip(root.split_evenly((1, shown.len()))) {
        draw_panel(&area, panel, curves, references, (z0, z1))?;
    }
    root.present()?;
    Ok(())
}

fn draw_panel(
    area: &Area<'_>,
    panel: &Panel,
    curves: &[(String, &dyn Columns)],
    references: &[Reference],
    (z0, z1): (f64, f64),
) -> anyhow::Result<()> {
    let ncols = panel.columns.len();
    let mut lines = Vec::new();
    for (ci, (label, prof)) in curves.iter().enumerate() {
        for (ki, &col) in panel.columns.iter().enumerate() {
            let mut pts = points(*prof, col, panel.log_x);
            pts.retain(|p| p.1 >= z0 && p.1 <= z1);
            if pts.is_empty() {
                continue;
            }
            let label = match (curves.len(), ncols) {
                (1, _) => col.to_string(),
                (_, 1) => label.clone(),
                _ => format!("{label} {col}"),
            };
            lines.push(Line { label, color: color(ci * ncols + ki), points: pts });
        }
    }
    let mut marks = Vec::new();
    for (ri, r) in references.iter().enumerate() {
        for (ki, &col) in panel.columns.iter().enumerate() {
            let all = points(r.table, col, panel.log_x);
            if all.is_empty() {
                continue;
            }
            let stride = all.len().div_ceil(MAX_MARKS).max(1);
            let pts: Vec<_> = all.into_iter().step_by(stride).filter(|p| p.1 >= z0 && p.1 <= z1).collect();
            let label = if ncols == 1 { r.label.to_string() } else { format!("{} {col}", r.label) };
            let color = if curves.len() == 1 { color(ki) } else { BLACK };
            marks.push(Marks { label, color, triangle: (ri + ki) % 2 == 1, points: pts });
        }
    }
    let xs = lines.iter().flat_map(|l| &l.points).chain(marks.iter().flat_map(|m| &m.points)).map(|p| p.0);
    let (x0, x1) = axis_range(xs, panel.log_x);
    let mut builder = PANEL.on(area, panel.title);
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            let log_label = |x: &f64| format!("{x:.0e}");
            let mut mesh = chart.configure_mesh();
            mesh.x_desc(panel.x_desc).y_desc("z [m]").x_labels(6).label_style(("sans-serif", 14));
            if panel.log_x {
                mesh.x_label_formatter(&log_label);
            }
            mesh.draw()?;
            for m in &marks {
                let color = m.color;
                let inside = m.points.iter().copied().filter(|p| p.0 >= x0 && p.0 <= x1);
                if m.triangle {
                    chart
                        .draw_series(inside.map(|p| TriangleMarker::new(p, 4, color.stroke_width(1))))?
                        .label(m.label.as_str())
                        .legend(triangle_key(color.stroke_width(1), 4));
                } else {
                    chart
                        .draw_series(inside.map(|p| Circle::new(p, 3, color.stroke_width(1))))?
                        .label(m.label.as_str())
                        .legend(circle_key(color.stroke_width(1), 3));
                }
            }
            for l in &lines {
                let color = l.color;
                let pts = l.points.iter().map(|&(x, z)| (x.clamp(x0, x1), z));
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                    .label(l.label.as_str())
                    .legend(line_key(color, 2));
            }
            legend(&mut chart, panel.legend.clone(), 13)?;
        }};
    }
    if panel.log_x {
        body!(builder.build_cartesian_2d((x0..x1).log_scale(), z0..z1)?);
    } else {
        body!(builder.build_cartesian_2d(x0..x1, z0..z1)?);
    }
    Ok(())
}
