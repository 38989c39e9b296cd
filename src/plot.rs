//! `saltus closure plot`: closure curves side by side.
//!
//! A closure comparison file (see `cases/closures/`) holds figures; each figure sweeps one
//! input of one family over a range for several models, writes `<name>.csv` (the swept
//! input then one column per model) and `<name>.png` ([`crate::figures::closures`]).

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use serde::Deserialize;

use crate::eval::{evaluate, parse_model, EvalFamily};
use crate::figures::closures::{self, Curves};
use crate::figures::register_font;
use crate::table::Table;

/// Most points of a figure's sweep.
const MAX_POINTS: usize = 100_000;
/// Most decades a logarithmic sweep spans.
const MAX_DECADES: f64 = 200.0;

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
        let family = EvalFamily::from_key(&fig.family).with_context(|| format!("{origin}: {key}.family"))?;
        let [a, b] = fig.range;
        let sweep = (2..=MAX_POINTS).contains(&fig.points) && a < b && (b - a).is_finite();
        if !sweep || (fig.log_x && !(a > 0.0 && (b / a).log10() <= MAX_DECADES)) {
            bail!(
                "{origin}: {key}: need points from 2 to {MAX_POINTS} and a range [from, to] of finite numbers with from < to and a finite span to - from (on a log axis from > 0 and at most {MAX_DECADES} decades)"
            );
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
        let caption = if cmp.title.is_empty() { fig.name.clone() } else { format!("{}: {}", cmp.title, fig.name) };
        let axes =
            Curves { caption: &caption, x: &fig.x, y: &fig.y, range: fig.range, log_x: fig.log_x, log_y: fig.log_y };
        closures::draw(&axes, &result, &png).with_context(|| format!("{}: cannot draw", png.display()))?;
        written.push(png);
    }
    Ok(written)
}
