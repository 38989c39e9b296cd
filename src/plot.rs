//! `saltus closure plot`: closure curves side by side, from a comparison file.
//!
//! A comparison file (see `cases/closures/`) holds figures; each figure sweeps one input
//! of one family over a range for several models, writes `<name>.csv` (the swept input
//! then one column per model) and `<name>.png`.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use plotters::prelude::*;
use serde::Deserialize;

use crate::eval::{evaluate, parse_model, EvalFamily};
use crate::table::Table;

/// A closure comparison file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Comparison {
    /// title printed on every figure
    #[serde(default)]
    pub title: String,
    /// figures
    #[serde(rename = "figure")]
    pub figures: Vec<Figure>,
}

/// One figure: one family, one swept input, one output, several models.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Figure {
    /// file stem of the outputs
    pub name: String,
    /// family, as in `closure eval --family`
    pub family: String,
    /// swept input column
    pub x: String,
    /// plotted output column
    pub y: String,
    /// sweep range [from, to]
    pub range: [f64; 2],
    /// number of points
    #[serde(default = "default_points")]
    pub points: usize,
    /// logarithmic x axis (and sweep)
    #[serde(default)]
    pub log_x: bool,
    /// logarithmic y axis
    #[serde(default)]
    pub log_y: bool,
    /// other inputs held constant
    #[serde(default)]
    pub fixed: toml::Table,
    /// models compared
    #[serde(rename = "model")]
    pub models: Vec<Curve>,
}

/// One curve.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Curve {
    /// legend label
    pub label: String,
    /// closure table
    pub model: toml::Table,
}

fn default_points() -> usize {
    200
}

fn family_of(name: &str) -> anyhow::Result<EvalFamily> {
    EvalFamily::ALL.into_iter().find(|f| f.key() == name).ok_or_else(|| {
        anyhow!(
            "unknown family `{name}`; known: {}",
            EvalFamily::ALL.iter().map(|f| f.key()).collect::<Vec<_>>().join(", ")
        )
    })
}

/// Read a comparison file.
pub fn load(path: &Path) -> anyhow::Result<Comparison> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let table = saltus_core::scene::parse_table(&text, path)?;
    serde_path_to_error::deserialize(toml::Value::Table(table))
        .map_err(|e| anyhow!("{}: key `{}`: {}", path.display(), e.path(), e.inner()))
}

/// Evaluate and draw every figure; returns the files written.
pub fn run(path: &Path, out_dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    register_font()?;
    let cmp = load(path)?;
    let origin = path.display().to_string();
    let mut written = Vec::new();
    for (fi, fig) in cmp.figures.iter().enumerate() {
        let key = format!("figure[{fi}]");
        let family = family_of(&fig.family).with_context(|| format!("{origin}: {key}.family"))?;
        let [a, b] = fig.range;
        if fig.points < 2 || !(a.is_finite() && b.is_finite() && a < b) || (fig.log_x && a <= 0.0) {
            bail!("{origin}: {key}: need points >= 2 and a range [from, to] with from < to (from > 0 on a log axis)");
        }
        let xs: Vec<f64> = (0..fig.points)
            .map(|i| {
                let t = i as f64 / (fig.points - 1) as f64;
                if fig.log_x {
                    (a.ln() + t * (b.ln() - a.ln())).exp()
                } else {
                    a + t * (b - a)
                }
            })
            .collect();
        let mut input = Table::default();
        input.push(fig.x.clone(), xs.clone());
        for (k, v) in &fig.fixed {
            let v = v
                .as_float()
                .or_else(|| v.as_integer().map(|i| i as f64))
                .ok_or_else(|| anyhow!("{origin}: {key}.fixed.{k}: expected a number"))?;
            input.push(k.clone(), vec![v; xs.len()]);
        }
        let mut result = Table::default();
        result.push(fig.x.clone(), xs.clone());
        for (mi, curve) in fig.models.iter().enumerate() {
            let model = parse_model(&toml::to_string(&curve.model)?, family)?;
            let t = evaluate(family, model, &input, &format!("{origin}: {key}.model[{mi}]"), 0)
                .with_context(|| format!("{origin}: {key}.model[{mi}] ({})", curve.label))?;
            let y = t.get(&fig.y).ok_or_else(|| {
                anyhow!(
                    "{origin}: {key}.y: `{}` is not an output of {}; outputs: {}",
                    fig.y,
                    family.key(),
                    family.outputs().join(", ")
                )
            })?;
            result.push(curve.label.clone(), y.to_vec());
        }
        std::fs::create_dir_all(out_dir).with_context(|| format!("{}: cannot create", out_dir.display()))?;
        let csv = out_dir.join(format!("{}.csv", fig.name));
        result.write_csv_file(&csv)?;
        written.push(csv);
        let png = out_dir.join(format!("{}.png", fig.name));
        draw(&cmp.title, fig, &result, &png).with_context(|| format!("{}: cannot draw", png.display()))?;
        written.push(png);
    }
    Ok(written)
}

/// Register the bundled font once (plotters draws text with ab_glyph, no system fonts).
pub fn register_font() -> anyhow::Result<()> {
    static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| anyhow!("bundled font is invalid"))
}

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

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
        (lo / 1.2, hi * 1.2)
    } else {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

fn draw(title: &str, fig: &Figure, t: &Table, png: &Path) -> anyhow::Result<()> {
    let root = BitMapBackend::new(png, (900, 620)).into_drawing_area();
    root.fill(&WHITE)?;
    let caption = if title.is_empty() { fig.name.clone() } else { format!("{title}: {}", fig.name) };
    let (x0, x1) = (fig.range[0], fig.range[1]);
    let (y0, y1) = finite_range(t, fig.log_y);
    let mut builder = ChartBuilder::on(&root);
    builder.caption(caption, ("sans-serif", 24)).margin(15).x_label_area_size(45).y_label_area_size(70);
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(fig.x.as_str())
                .y_desc(fig.y.as_str())
                .label_style(("sans-serif", 15))
                .draw()?;
            let xs = &t.columns[0];
            for (i, (name, ys)) in t.names[1..].iter().zip(&t.columns[1..]).enumerate() {
                let color = COLORS[i % COLORS.len()];
                let pts: Vec<(f64, f64)> = xs
                    .iter()
                    .zip(ys)
                    .filter(|(x, y)| y.is_finite() && (!fig.log_y || **y > 0.0) && x.is_finite())
                    .map(|(&x, &y)| (x, y.clamp(y0, y1)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                    .label(name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 15))
                .draw()?;
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
