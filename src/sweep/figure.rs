//! The study's figure: qs* against the swept Shields number, log-log, with the 3/2-law
//! fit, the classic bedload laws and, when present, the Meyer-Peter & Mueller (1948)
//! flume data as compiled by Recking (2010).

use std::path::Path;

use anyhow::{bail, Context};
use plotters::prelude::*;

use super::fit::Fit;
use crate::plot::{register_font, COLORS};

/// File name of the figure in the sweep's folder.
pub const FIGURE: &str = "sweep.png";

/// The classic laws drawn for comparison, qs* = a (theta - theta_c)^{3/2}: label, a,
/// theta_c. Reference curves from the literature, not models the solvers use.
pub const CLASSIC_LAWS: [(&str, f64, f64); 3] = [
    // Meyer-Peter & Mueller 1948
    ("Meyer-Peter & Mueller 8 (theta - 0.047)^1.5", 8.0, 0.047),
    // Wong & Parker 2006, the corrected MPM fit
    ("Wong & Parker 3.97 (theta - 0.0495)^1.5", 3.97, 0.0495),
    // Wilson 1987 (sheet flow), with the threshold drawn in Maurin et al. 2015 figure 6
    ("Wilson 11.8 (theta - 0.04)^1.5", 11.8, 0.04),
];

use super::series::{Mark, Series};

/// A tick label: a few digits without trailing zeros, powers of ten far from 1.
fn tidy(v: f64) -> String {
    if (1e-3..1e4).contains(&v.abs()) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

/// Read the flume data: (Shields stress, dimensionless bedload flux) of each row.
pub fn read_mpm(path: &Path) -> anyhow::Result<Vec<(f64, f64)>> {
    let mut r = csv::Reader::from_path(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let header = r.headers()?.clone();
    let col = |name: &str| header.iter().position(|h| h.trim() == name);
    let (Some(x), Some(y)) = (col("Shields stress"), col("dimensionless bedload flux per unit width")) else {
        bail!("{}: no `Shields stress` and `dimensionless bedload flux per unit width` columns", path.display());
    };
    let mut out = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let rec = rec.with_context(|| format!("{}: row {}", path.display(), i + 2))?;
        let num = |k: usize| rec.get(k).and_then(|c| c.trim().parse::<f64>().ok()).filter(|v| v.is_finite());
        if let (Some(a), Some(b)) = (num(x), num(y)) {
            out.push((a, b));
        }
    }
    Ok(out)
}

/// Draw each series (with error bars) with its fit, the `laws` (label, a, theta_c) and
/// `data` into `png`.
#[allow(clippy::too_many_arguments)]
pub fn draw(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    fits: &[(String, Fit)],
    laws: &[(&str, f64, f64)],
    data: &[(f64, f64)],
    png: &Path,
) -> anyhow::Result<()> {
    register_font()?;
    let all: Vec<(usize, Mark)> = series
        .iter()
        .enumerate()
        .flat_map(|(k, s)| s.marks.iter().map(move |m| (k, *m)))
        .filter(|(_, (x, y, _))| *x > 0.0 && *y > 0.0)
        .collect();
    let pos: Vec<_> = all.iter().map(|(_, m)| *m).collect();
    if pos.is_empty() {
        bail!("no point with {x_desc} > 0 and {y_desc} > 0 to draw on log axes");
    }
    let xs = pos.iter().map(|m| m.0).chain(data.iter().map(|d| d.0));
    let ys = pos.iter().map(|m| m.1).chain(data.iter().map(|d| d.1).filter(|y| *y > 0.0));
    let (x0, x1) = xs.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    let (x0, x1) = (x0 / 1.3, x1 * 1.3);
    let (y0, y1) = (y0 / 2.0, y1 * 2.0);
    let root = BitMapBackend::new(png, (900, 680)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| tidy(*v))
        .y_label_formatter(&|v| tidy(*v))
        .label_style(("sans-serif", 15))
        .draw()?;
    let curve = |a: f64, c: f64| {
        (0..=400).filter_map(move |k| {
            let x = x0 * (x1 / x0).powf(k as f64 / 400.0);
            let y = a * (x - c).max(0.0).powf(1.5);
            (y >= y0 && y <= y1).then_some((x, y))
        })
    };
    for (i, (label, a, c)) in laws.iter().enumerate() {
        let color = COLORS[(i + 2) % COLORS.len()];
        chart
            .draw_series(LineSeries::new(curve(*a, *c), color.stroke_width(1)))?
            .label(*label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(1)));
    }
    if !data.is_empty() {
        let color = RGBColor(120, 120, 120);
        let inside = data.iter().copied().filter(|(x, y)| *x >= x0 && *x <= x1 && *y >= y0 && *y <= y1);
        chart
            .draw_series(inside.map(|p| Cross::new(p, 3, color.stroke_width(1))))?
            .label("Meyer-Peter & Mueller 1948 flume data (Recking 2010)")
            .legend(move |(x, y)| Cross::new((x + 10, y), 3, color.stroke_width(1)));
    }
    // one colour per series: its points and its fit
    let series_color = |k: usize| if k == 0 { COLORS[0] } else { COLORS[(k + 4) % COLORS.len()] };
    for (k, s) in series.iter().enumerate() {
        let color = series_color(k);
        let name = if s.label.is_empty() { "this sweep".to_string() } else { s.label.clone() };
        if let Some((_, f)) = fits.iter().find(|(l, _)| l == &s.label) {
            let bound = if f.at_bound { ", theta_c at the smallest theta" } else { "" };
            let label = format!(
                "{name}: {:.3} (+- {:.2}) (theta - {:.4} (+- {:.4}))^1.5, {} points{bound}",
                f.a, f.a_stderr, f.theta_c, f.theta_c_stderr, f.n
            );
            chart
                .draw_series(LineSeries::new(curve(f.a, f.theta_c), color.stroke_width(2)))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
        }
        let mine: Vec<Mark> = all.iter().filter(|(j, _)| *j == k).map(|(_, m)| *m).collect();
        for &(x, y, e) in &mine {
            if let Some(e) = e.filter(|e| *e > 0.0) {
                let lo = (y - e).max(y0);
                chart.draw_series(LineSeries::new([(x, lo), (x, (y + e).min(y1))], color.stroke_width(1)))?;
            }
        }
        chart
            .draw_series(mine.iter().map(|&(x, y, _)| Circle::new((x, y), 4, color.filled())))?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    root.present()?;
    Ok(())
}
