//! Closure curves against one swept input: one line per model, the input on x, one
//! output on y, either axis logarithmic.

use std::path::Path;

use plotters::prelude::*;

use super::{canvas, color, legend, line_key, Frame, PAGE};
use crate::table::Table;

/// The axes of a closure figure.
#[derive(Clone, Copy, Debug)]
pub struct Curves<'a> {
    /// caption above the chart
    pub caption: &'a str,
    /// name of the swept input (x axis)
    pub x: &'a str,
    /// name of the drawn output (y axis)
    pub y: &'a str,
    /// x range [from, to]
    pub range: [f64; 2],
    /// logarithmic x axis
    pub log_x: bool,
    /// logarithmic y axis
    pub log_y: bool,
}

fn finite_range(t: &Table, log: bool) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for c in &t.columns[1..] {
        for &v in c.iter().filter(|v| v.is_finite() && (!log || **v > 0.0)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        return (if log { 1e-3 } else { 0.0 }, 1.0);
    }
    if hi <= lo {
        hi = lo + lo.abs().max(1.0) * 0.1;
    }
    if log {
        super::log_span(lo, hi, 1.2)
    } else {
        super::linear_span(lo, hi, 0.05)
    }
}

/// Draw every column of `t` after the first against the first, one line per column
/// labelled with its name, on the axes of `fig`, into `png`.
pub fn draw(fig: &Curves, t: &Table, png: &Path) -> anyhow::Result<()> {
    let root = canvas(png, (900, 620))?;
    let (x0, x1) =
        if fig.log_x { super::log_span(fig.range[0], fig.range[1], 1.0) } else { (fig.range[0], fig.range[1]) };
    let (y0, y1) = finite_range(t, fig.log_y);
    let mut builder = Frame { caption: 24, ..PAGE }.on(&root, fig.caption);
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart.configure_mesh().x_desc(fig.x).y_desc(fig.y).label_style(("sans-serif", 15)).draw()?;
            let xs = &t.columns[0];
            for (i, (name, ys)) in t.names[1..].iter().zip(&t.columns[1..]).enumerate() {
                let color = color(i);
                let pts: Vec<(f64, f64)> = xs
                    .iter()
                    .zip(ys)
                    .filter(|(x, y)| y.is_finite() && (!fig.log_y || **y > 0.0) && x.is_finite())
                    .map(|(&x, &y)| (x, y.clamp(y0, y1)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                    .label(name.as_str())
                    .legend(line_key(color, 2));
            }
            legend(&mut chart, SeriesLabelPosition::MiddleRight, 15)?;
        }};
    }
    match (fig.log_x, fig.log_y) {
        (true, true) => body!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?),
        (true, false) => body!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)?),
        (false, true) => body!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())?),
        (false, false) => body!(builder.build_cartesian_2d(x0..x1, y0..y1)?),
    }
    root.present()?;
    Ok(())
}
