//! Work against precision: errors against the cost of each run on log-log axes, one
//! symbol colour per measure of the error, the first measure with its statistical bars
//! and the runs' names.

use std::path::Path;

use anyhow::Context;
use plotters::prelude::*;

use super::{canvas, circle_key, color, error_bars, legend, PAGE};

/// One run's point: its cost, its error, the error's statistical bar, its name.
#[derive(Clone, Copy, Debug)]
pub struct Mark<'a> {
    /// cost (s)
    pub cost: f64,
    /// error, > 0
    pub error: f64,
    /// statistical error of the error, drawn as a bar
    pub bar: Option<f64>,
    /// the run's name, written beside the point
    pub name: &'a str,
}

/// The points of one measure of the error.
#[derive(Clone, Debug)]
pub struct Measure<'a> {
    /// legend label
    pub label: &'a str,
    /// its points
    pub marks: Vec<Mark<'a>>,
}

/// Draw the `measures` against cost into `png`; the bars and names of the first measure
/// are drawn, a difference inside its bar being not resolved.
pub fn draw(title: &str, x_desc: &str, measures: &[Measure], png: &Path) -> anyhow::Result<()> {
    let marks = measures.iter().flat_map(|m| &m.marks);
    let bars = measures.iter().take(1).flat_map(|m| &m.marks).filter_map(|m| m.bar.filter(|b| *b > 0.0));
    let (x0, x1) = marks.clone().fold((f64::INFINITY, 0.0f64), |(a, b), m| (a.min(m.cost), b.max(m.cost)));
    let (y0, y1) = marks.map(|m| m.error).chain(bars).fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    let ((x0, x1), (y0, y1)) = (super::log_span(x0, x1, 1.5), super::log_span(y0, y1, 2.0));
    let root = canvas(png, (900, 680))?;
    let mut chart = PAGE.on(&root, title).build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("error against the reference")
        .label_style(("sans-serif", 15))
        .draw()?;
    for (k, measure) in measures.iter().enumerate() {
        let color = color(k);
        let mine = &measure.marks;
        if mine.is_empty() {
            continue;
        }
        if k == 0 {
            let bars = mine.iter().filter_map(|m| Some((m.cost, m.error, m.bar?)));
            chart.draw_series(error_bars(bars, (y0, y1), color.stroke_width(1)))?;
            chart.draw_series(mine.iter().map(|m| {
                Text::new(format!(" {}", m.name), (m.cost, m.error), ("sans-serif", 12).into_font().color(&BLACK))
            }))?;
        }
        chart
            .draw_series(mine.iter().map(|m| Circle::new((m.cost, m.error), 4, color.filled())))?
            .label(measure.label)
            .legend(circle_key(color.filled(), 4));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight, 13)?;
    root.present().with_context(|| format!("{}: cannot write", png.display()))?;
    Ok(())
}
