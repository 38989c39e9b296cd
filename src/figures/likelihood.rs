//! Profile likelihoods of fitted constants, one panel per constant: chi^2 - chi^2_min with
//! the other constants refitted (symbols) against the Laplace approximation
//! ((p - p_opt) / stderr)^2 (line).

use std::path::Path;

use plotters::prelude::*;

use super::{canvas, circle_key, color, legend, line_key, Frame, PANEL};

/// One fitted constant's panel.
#[derive(Clone, Debug)]
pub struct Constant<'a> {
    /// its key (the panel's caption)
    pub key: &'a str,
    /// the optimum
    pub value: f64,
    /// its statistical standard error (no line when not positive)
    pub stderr: f64,
    /// (value, chi^2 - chi^2_min) of each refit
    pub profile: Vec<(f64, f64)>,
}

/// Draw one panel per constant side by side into `png`.
pub fn draw(constants: &[Constant], png: &Path) -> anyhow::Result<()> {
    let n = constants.len().max(1);
    let root = canvas(png, (420 * n as u32 + 20, 440))?;
    let root = root.titled("profile likelihoods", ("sans-serif", 20))?;
    for (f, area) in constants.iter().zip(root.split_evenly((1, n))) {
        let pts: Vec<(f64, f64)> = f.profile.iter().copied().filter(|p| p.1.is_finite()).collect();
        let (x0, x1) = pts.iter().fold((f.value, f.value), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (x0, x1) = if x1 > x0 { (x0, x1) } else { (f.value - 1.0, f.value + 1.0) };
        let sigma = f.stderr;
        let laplace = |x: f64| if sigma > 0.0 { ((x - f.value) / sigma).powi(2) } else { f64::NAN };
        let ymax = pts
            .iter()
            .map(|p| p.1)
            .chain((0..=40).map(|i| laplace(x0 + (x1 - x0) * i as f64 / 40.0)))
            .filter(|v| v.is_finite())
            .fold(1.0f64, f64::max)
            * 1.1;
        let frame = Frame { caption: 15, x_area: 40, y_area: 60, ..PANEL };
        let mut chart = frame.on(&area, f.key).build_cartesian_2d(x0..x1, 0.0..ymax)?;
        chart.configure_mesh().x_desc("value").y_desc("chi2 - chi2_min").label_style(("sans-serif", 13)).draw()?;
        if sigma > 0.0 {
            let line =
                (0..=80).map(|i| x0 + (x1 - x0) * i as f64 / 80.0).map(|x| (x, laplace(x))).filter(|p| p.1 <= ymax);
            chart
                .draw_series(LineSeries::new(line, color(0).stroke_width(2)))?
                .label("Laplace approximation")
                .legend(line_key(color(0), 2));
        }
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color(1).filled())))?
            .label("others refitted")
            .legend(circle_key(color(1).filled(), 4));
        legend(&mut chart, SeriesLabelPosition::UpperMiddle, 12)?;
    }
    root.present()?;
    Ok(())
}
