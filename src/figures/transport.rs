//! qs* against the Shields number on log-log axes: the points of each series with their
//! error bars and their 3/2-law fit, the classic bedload laws, and flume data.

use std::path::Path;

use anyhow::bail;
use plotters::prelude::*;
use saltus_solvers::measures::bedload::TransportLaw;

use super::{canvas, circle_key, color, cross_key, error_bars, legend, line_key, PAGE};

/// One point of a series: x, y, the error of y.
pub type Mark = (f64, f64, Option<f64>);

/// The points of one series and the law fitted on them.
#[derive(Clone, Debug)]
pub struct Series<'a> {
    /// legend label of the points
    pub label: String,
    /// the points
    pub marks: &'a [Mark],
    /// the fitted law and its legend label
    pub fit: Option<(String, TransportLaw)>,
}

/// Measured points drawn as crosses, with their legend label.
#[derive(Clone, Copy, Debug)]
pub struct Data<'a> {
    /// legend label
    pub label: &'a str,
    /// (x, y) of each point
    pub points: &'a [(f64, f64)],
}

/// A tick label: a few digits without trailing zeros, powers of ten far from 1.
fn tidy(v: f64) -> String {
    if (1e-3..1e4).contains(&v.abs()) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

/// Draw the `laws`, the `data` and each series (its fit, then its points with error bars)
/// into `png`; the axes span the positive points and data.
pub fn draw(
    title: &str,
    (x_desc, y_desc): (&str, &str),
    series: &[Series],
    laws: &[TransportLaw],
    data: Data,
    png: &Path,
) -> anyhow::Result<()> {
    let all: Vec<(usize, Mark)> = series
        .iter()
        .enumerate()
        .flat_map(|(k, s)| s.marks.iter().map(move |m| (k, *m)))
        .filter(|(_, (x, y, _))| *x > 0.0 && *y > 0.0)
        .collect();
    if all.is_empty() {
        bail!("no point with {x_desc} > 0 and {y_desc} > 0 to draw on log axes");
    }
    let xs = all.iter().map(|(_, m)| m.0).chain(data.points.iter().map(|d| d.0));
    let ys = all.iter().map(|(_, m)| m.1).chain(data.points.iter().map(|d| d.1).filter(|y| *y > 0.0));
    let (x0, x1) = xs.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    let (x0, x1) = super::log_span(x0, x1, 1.3);
    let (y0, y1) = super::log_span(y0, y1, 2.0);
    let root = canvas(png, (900, 680))?;
    let mut chart = PAGE.on(&root, title).build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| tidy(*v))
        .y_label_formatter(&|v| tidy(*v))
        .label_style(("sans-serif", 15))
        .draw()?;
    let curve = |law: TransportLaw| {
        (0..=400).filter_map(move |k| {
            let x = x0 * (x1 / x0).powf(k as f64 / 400.0);
            let y = law.qs_star(x);
            (y >= y0 && y <= y1).then_some((x, y))
        })
    };
    for (i, law) in laws.iter().enumerate() {
        let color = color(i + 2);
        chart
            .draw_series(LineSeries::new(curve(*law), color.stroke_width(1)))?
            .label(law.label())
            .legend(line_key(color, 1));
    }
    if !data.points.is_empty() {
        let gray = RGBColor(120, 120, 120);
        let inside = data.points.iter().copied().filter(|(x, y)| *x >= x0 && *x <= x1 && *y >= y0 && *y <= y1);
        chart
            .draw_series(inside.map(|p| Cross::new(p, 3, gray.stroke_width(1))))?
            .label(data.label)
            .legend(cross_key(gray.stroke_width(1), 3));
    }
    // one colour per series: its points and its fit
    let series_color = |k: usize| if k == 0 { color(0) } else { color(k + 4) };
    for (k, s) in series.iter().enumerate() {
        let color = series_color(k);
        if let Some((label, law)) = &s.fit {
            chart
                .draw_series(LineSeries::new(curve(*law), color.stroke_width(2)))?
                .label(label.as_str())
                .legend(line_key(color, 2));
        }
        let mine: Vec<Mark> = all.iter().filter(|(j, _)| *j == k).map(|(_, m)| *m).collect();
        let bars = mine.iter().filter_map(|&(x, y, e)| Some((x, y, e?)));
        chart.draw_series(error_bars(bars, (y0, y1), color.stroke_width(1)))?;
        chart
            .draw_series(mine.iter().map(|&(x, y, _)| Circle::new((x, y), 4, color.filled())))?
            .label(s.label.as_str())
            .legend(circle_key(color.filled(), 4));
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft, 13)?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points at the ends of the double range (a flume table with 1e308 or 1e-308 in it)
    /// draw a figure: the log axes keep finite, positive ends.
    #[test]
    fn points_at_the_ends_of_the_double_range_draw() {
        let dir = std::env::temp_dir().join(format!("saltus_transport_figure_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let png = dir.join("extreme.png");
        let marks: Vec<Mark> = vec![(1e308, 1e308, None), (1e-308, 1e-308, Some(1e-308)), (0.5, 1.0, Some(0.1))];
        let series = [Series { label: "extremes".into(), marks: &marks, fit: None }];
        let data = Data { label: "flume", points: &[(f64::MAX, f64::MIN_POSITIVE)] };
        draw("extremes", ("theta", "qs*"), &series, &[], data, &png).unwrap();
        assert!(png.is_file());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
