//! `saltus compare`: one base scene, several variants of it (each a list of `--set`
//! overrides, after those of the command line), run in parallel; one table of their summaries with their RMS differences
//! from the base scene's reference data, and one figure of their profiles over that data.
//!
//! ```toml
//! base = "case01.toml"            # scene file, relative to this file
//! [meta]
//! name = "my_comparison"          # output folder out/<name> (default: this file's stem)
//! description = "..."
//! [[variant]]
//! name = "stokes drag"            # table row, legend label, folder <DIR>/stokes-drag
//! set = ['closures.drag={type="stokes"}']
//! [[variant]]
//! name = "as is"
//! set = []
//! [reference]                     # optional: work against precision (module precision)
//! variant = "as is"               # or data = true (the base scene's reference data)
//! # qs_star = 2.44                # and/or a published qs*, with qs_star_stderr
//! # smooth = 1.0                  # with a variant: Fry's eq-11 Gaussian of h_g = 1 d on the
//! # align = true                  # moving-layer RMS, and each profile from its bed surface
//! ```

pub mod differences;
pub mod precision;

use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget};
use rayon::prelude::*;
use saltus_core::scene::{Meta, Scene};
use saltus_solvers::RunReport;
use serde::Deserialize;

use crate::figures::profiles::{self, Reference, COMPARE_PANELS};
use crate::figures::register_font;
use crate::runner;
use crate::study_file::{self, key_error};
use precision::ReferenceSpec;

/// File names written in the output folder, next to one folder per variant.
pub const TABLE: &str = "comparison.csv";
/// See [`TABLE`].
pub const FIGURE: &str = "comparison.png";

/// Columns of the comparison table, after `variant` and before `error`.
pub const COLUMNS: [&str; 14] = [
    "solver",
    "qs_star",
    "qs",
    "shields",
    "bed_height",
    "transport_layer_thickness",
    "flux_layer_thickness",
    "steady",
    "sim_time_s",
    "steps",
    "wall_time_s",
    "mass_error",
    "net_transport",
    "net_transport_stderr",
];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    base: String,
    #[serde(default)]
    meta: Meta,
    #[serde(default, rename = "variant")]
    variants: Vec<Variant>,
    #[serde(default)]
    reference: Option<ReferenceSpec>,
}

/// One variant: the base scene with overrides.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Variant {
    /// table row and legend label; its slug names the variant's output folder
    pub name: String,
    /// `KEY=VALUE` overrides, as `saltus run --set`
    #[serde(default)]
    pub set: Vec<String>,
    /// closures file whose `[closures.<family>]` tables replace the base scene's, as
    /// `saltus run --closures` (relative to the compare file), before the overrides
    #[serde(default)]
    pub closures: Option<PathBuf>,
}

/// A loaded and checked compare file.
#[derive(Debug)]
pub struct Comparison {
    /// the compare file
    pub file: PathBuf,
    /// the base scene file (resolved against the compare file's folder)
    pub base: PathBuf,
    /// name (never empty: the file stem when not given) and description
    pub meta: Meta,
    /// variants, in file order, at least one
    pub variants: Vec<Variant>,
    /// `KEY=VALUE` overrides of the command line, applied to every variant before its own
    pub set: Vec<String>,
    /// what the variants' errors are measured against, for the work-precision table
    pub reference: Option<ReferenceSpec>,
}

/// Lower-case letters and digits of `name`, other runs of characters replaced by `-`.
pub fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_alphanumeric() {
            s.extend(c.to_lowercase());
        } else if !s.is_empty() && !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_end_matches('-').to_string()
}

/// Read and check a compare file: TOML syntax, keys, variant names, and the base scene
/// (loaded once with the command line's overrides `set` only, so that a broken base fails
/// before any run).
pub fn load(path: &Path, set: &[String]) -> anyhow::Result<Comparison> {
    let (raw, _): (RawFile, _) = study_file::read(path)?;
    if raw.variants.is_empty() {
        return Err(key_error(path, "variant", "no [[variant]] table; give at least one, each with name and set"));
    }
    let mut names = HashSet::new();
    let mut slugs = HashSet::new();
    for (i, v) in raw.variants.iter().enumerate() {
        let key = format!("variant[{i}].name");
        let s = slug(&v.name);
        if s.is_empty() {
            return Err(key_error(path, key, format!("`{}`: a name needs at least one letter or digit", v.name)));
        }
        if !names.insert(v.name.as_str()) {
            return Err(key_error(path, key, format!("`{}` is used by an earlier variant", v.name)));
        }
        if !slugs.insert(s.clone()) {
            return Err(key_error(
                path,
                key,
                format!("`{}` gives the same output folder `{s}` as an earlier variant", v.name),
            ));
        }
    }
    if let Some(r) = &raw.reference {
        check_reference(path, r, &raw.variants)?;
    }
    let mut variants = raw.variants;
    for (i, v) in variants.iter_mut().enumerate() {
        if let Some(c) = v.closures.take() {
            v.closures = Some(study_file::closures_file(path, format!("variant[{i}].closures"), &c)?);
        }
    }
    let base = study_file::base_scene(path, &raw.base)?;
    Scene::from_file_with(&base, set)
        .map_err(|e| key_error(path, "base", format!("the base scene is invalid: {e}")))?;
    let meta = study_file::named(raw.meta, path, "comparison");
    Ok(Comparison { file: path.to_path_buf(), base, meta, variants, set: set.to_vec(), reference: raw.reference })
}

/// A `[reference]` names a variant of the file, or the data, or a finite positive qs*.
fn check_reference(path: &Path, r: &ReferenceSpec, variants: &[Variant]) -> anyhow::Result<()> {
    if let Some(v) = &r.variant {
        if !variants.iter().any(|w| &w.name == v) {
            let names: Vec<&str> = variants.iter().map(|w| w.name.as_str()).collect();
            return Err(key_error(path, "reference.variant", format!("`{v}` is not a variant; one of {names:?}")));
        }
        if r.data || r.qs_star.is_some() {
            return Err(key_error(
                path,
                "reference",
                "either a variant, or the data and/or a published qs_star, not both",
            ));
        }
    } else if !r.data && r.qs_star.is_none() {
        return Err(key_error(path, "reference", "give variant = \"<name>\", data = true or qs_star = <value>"));
    }
    for (key, v) in [("qs_star", r.qs_star), ("qs_star_stderr", r.qs_star_stderr)] {
        if let Some(v) = v.filter(|v| !(v.is_finite() && *v >= 0.0 && (key != "qs_star" || *v > 0.0))) {
            return Err(key_error(
                path,
                format!("reference.{key}"),
                format!("{v}: a finite number > 0 (>= 0 for an error)"),
            ));
        }
    }
    if r.qs_star_stderr.is_some() && r.qs_star.is_none() {
        return Err(key_error(path, "reference.qs_star_stderr", "an error of a qs_star the table does not give"));
    }
    precision::check_smooth(path, r.smooth)?;
    if (r.smooth.is_some() || r.align) && r.variant.is_none() {
        let key = if r.smooth.is_some() { "reference.smooth" } else { "reference.align" };
        return Err(key_error(
            path,
            key,
            "smooths or aligns the profiles of a reference variant: give variant = \"<name>\"",
        ));
    }
    Ok(())
}

/// Output folder when `--out` is not given: `out/<meta.name>`.
pub fn default_out(c: &Comparison) -> PathBuf {
    PathBuf::from("out").join(&c.meta.name)
}

/// One variant's run.
#[derive(Debug)]
pub struct VariantRun {
    /// variant name
    pub name: String,
    /// its output folder
    pub dir: PathBuf,
    /// summary and profiles (also of a run that broke down: its last good state)
    pub report: Option<RunReport>,
    /// why it failed (bad override, unstable run)
    pub error: Option<String>,
    /// warnings of the run
    pub warnings: Vec<String>,
}

/// Everything a comparison produced.
#[derive(Debug)]
pub struct CompareReport {
    /// output folder
    pub out: PathBuf,
    /// one per variant, in file order
    pub runs: Vec<VariantRun>,
    /// `comparison.csv`
    pub table: PathBuf,
    /// `comparison.png`, unless no variant left profiles or it could not be drawn
    pub figure: Option<PathBuf>,
    /// warnings of the runs and the figure, each once
    pub warnings: Vec<String>,
    /// profile columns compared with the base scene's reference data (`rms_<column>` in
    /// the table, after [`COLUMNS`]), see [`differences`]
    pub compared: Vec<String>,
    /// per variant, the RMS difference of each compared column (`None`: no run or no row)
    pub rms: Vec<Vec<Option<f64>>>,
    /// per variant, the bed-aligned metric ([`differences::ALIGNED`] columns, after the `rms_`
    /// ones); empty when the reference data have no `phi` column
    pub aligned: Vec<[Option<f64>; 4]>,
    /// per variant, its errors against the `[reference]` and its cost; empty without one
    pub precision: Vec<precision::Row>,
    /// `precision.csv`, with a `[reference]`
    pub precision_table: Option<PathBuf>,
    /// `precision.png`, with a `[reference]` and a row to draw
    pub precision_figure: Option<PathBuf>,
}

impl CompareReport {
    /// Number of variants that failed.
    pub fn failures(&self) -> usize {
        self.runs.iter().filter(|r| r.error.is_some()).count()
    }

    /// Header and one row of cells per variant (empty cells for a run without summary).
    pub fn rows(&self, precise: bool) -> (Vec<String>, Vec<Vec<String>>) {
        let mut header = vec!["variant".to_string()];
        header.extend(COLUMNS.iter().map(|c| c.to_string()));
        header.extend(self.compared.iter().map(|c| format!("rms_{c}")));
        if !self.aligned.is_empty() {
            header.extend(differences::ALIGNED.iter().map(|c| c.to_string()));
        }
        header.push("error".into());
        let rows = self
            .runs
            .iter()
            .enumerate()
            .map(|(k, r)| {
                let mut row = vec![r.name.clone()];
                match &r.report {
                    Some(rep) => row.extend(summary_cells(&rep.summary, precise)),
                    None => row.extend(COLUMNS.iter().map(|_| String::new())),
                }
                let aligned = self.aligned.get(k).into_iter().flatten();
                for e in self.rms.get(k).into_iter().flatten().chain(aligned) {
                    row.push(match (e, precise) {
                        (None, _) => String::new(),
                        (Some(v), true) => format!("{v:?}"),
                        (Some(v), false) => format!("{v:.4}"),
                    });
                }
                row.push(r.error.clone().unwrap_or_default());
                row
            })
            .collect();
        (header, rows)
    }

    /// The table as aligned text (numbers rounded, `-` for missing values).
    pub fn text_table(&self) -> String {
        let (header, rows) = self.rows(false);
        let rows: Vec<Vec<String>> = rows
            .into_iter()
            .map(|r| r.into_iter().map(|c| if c.is_empty() { "-".into() } else { c }).collect())
            .collect();
        let n = header.len();
        let width: Vec<usize> = (0..n)
            .map(|k| rows.iter().map(|r| r[k].chars().count()).chain([header[k].len()]).max().unwrap_or(0))
            .collect();
        let mut s = String::new();
        for row in std::iter::once(&header).chain(&rows) {
            let mut line = String::new();
            for (k, cell) in row.iter().enumerate() {
                let pad = width[k] - cell.chars().count();
                if k == 0 || k == n - 1 {
                    // text columns: left-aligned, the last one unpadded
                    line.push_str(cell);
                    if k == 0 {
                        line.push_str(&" ".repeat(pad));
                    }
                } else {
                    line.push_str(&" ".repeat(pad));
                    line.push_str(cell);
                }
                if k + 1 < n {
                    line.push_str("  ");
                }
            }
            let _ = writeln!(s, "{}", line.trim_end());
        }
        s
    }
}

fn summary_cells(s: &saltus_solvers::Summary, precise: bool) -> Vec<String> {
    if precise {
        let precise = |x: Option<f64>| x.map_or_else(String::new, |v| format!("{v:?}"));
        return vec![
            s.solver.clone(),
            precise(s.qs_star),
            precise(s.qs),
            precise(s.shields),
            precise(s.bed_height),
            precise(s.transport_layer_thickness),
            precise(s.flux_layer_thickness),
            s.steady.to_string(),
            format!("{:?}", s.sim_time_s),
            s.steps.to_string(),
            format!("{:?}", s.wall_time_s),
            s.mass_error.map_or_else(String::new, |m| format!("{m:?}")),
            precise(s.net_transport),
            precise(s.net_transport_stderr),
        ];
    }
    // an absent figure is an empty cell
    let rounded = |x: Option<f64>, f: fn(f64) -> String| x.map_or_else(String::new, f);
    vec![
        s.solver.clone(),
        rounded(s.qs_star, |v| format!("{v:.4}")),
        rounded(s.qs, |v| format!("{v:.4e}")),
        rounded(s.shields, |v| format!("{v:.3}")),
        rounded(s.bed_height, |v| format!("{v:.4}")),
        rounded(s.transport_layer_thickness, |v| format!("{v:.4}")),
        rounded(s.flux_layer_thickness, |v| format!("{v:.4}")),
        s.steady.to_string(),
        format!("{:.2}", s.sim_time_s),
        s.steps.to_string(),
        format!("{:.3}", s.wall_time_s),
        s.mass_error.map_or_else(String::new, |m| format!("{m:.1e}")),
        rounded(s.net_transport, |v| format!("{v:.3e}")),
        rounded(s.net_transport_stderr, |v| format!("{v:.1e}")),
    ]
}

/// Run every variant of `cmp` in parallel (one rayon task per variant), each into
/// `out/<slug of its name>`, then write `out/comparison.csv` and `out/comparison.png`.
/// A failing variant is recorded in its row; the others still run. With `progress`, one
/// progress bar per running variant on stderr.
pub fn run(cmp: &Comparison, out: &Path, progress: bool) -> anyhow::Result<CompareReport> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    register_font()?;
    let bars =
        if progress { MultiProgress::new() } else { MultiProgress::with_draw_target(ProgressDrawTarget::hidden()) };
    let runs: Vec<VariantRun> =
        cmp.variants.par_iter().with_max_len(1).map(|v| run_variant(cmp, v, out, &bars)).collect();

    let mut warnings: Vec<String> = Vec::new();
    for w in runs.iter().flat_map(|r| &r.warnings) {
        if !warnings.contains(w) {
            warnings.push(w.clone());
        }
    }
    // reference data of the base scene: RMS columns of the table, symbols of the figure
    let png = out.join(FIGURE);
    let base =
        Scene::from_file_with(&cmp.base, &cmp.set).with_context(|| format!("{}: key `base`", cmp.file.display()))?;
    let reference = match runner::load_reference(&base) {
        Ok(r) => r,
        Err(e) => {
            warnings.push(format!("{e:#}; no reference data in {} and {}", TABLE, png.display()));
            Vec::new()
        }
    };
    // each compared column from the first reference file that has it
    let sources: Vec<(String, &crate::table::Table)> = differences::COMPARED
        .iter()
        .filter_map(|c| reference.iter().find(|(_, t)| t.get(c).is_some()).map(|(_, t)| (c.to_string(), t)))
        .collect();
    let rms = runs
        .iter()
        .map(|r| {
            sources
                .iter()
                .map(|(c, t)| {
                    r.report.as_ref().and_then(|rep| differences::rms_difference(&rep.profiles, t, c)).map(|e| e.0)
                })
                .collect()
        })
        .collect();
    let compared = sources.into_iter().map(|(c, _)| c).collect();
    // the bed-aligned metric of a sheet flow, when the reference data have phi
    let tables: Vec<&crate::table::Table> = reference.iter().map(|(_, t)| t).collect();
    let aligned = if tables.iter().any(|t| t.get("phi").is_some()) {
        runs.iter()
            .map(|r| r.report.as_ref().and_then(|rep| differences::aligned(&rep.profiles, &tables)).unwrap_or_default())
            .collect()
    } else {
        Vec::new()
    };
    let mut report = CompareReport {
        out: out.to_path_buf(),
        runs,
        table: out.join(TABLE),
        figure: None,
        warnings,
        compared,
        rms,
        aligned,
        precision: Vec::new(),
        precision_table: None,
        precision_figure: None,
    };
    if let Some(spec) = &cmp.reference {
        let runs: Vec<(&str, Option<&RunReport>)> =
            report.runs.iter().map(|r| (r.name.as_str(), r.report.as_ref())).collect();
        if spec.data && tables.is_empty() {
            report
                .warnings
                .push(format!("{}: reference.data: the base scene has no reference data", cmp.file.display()));
        }
        report.precision = precision::rows(spec, &runs, &tables, base.particles.diameter);
        report.precision_table = Some(precision::write(&report.precision, out)?);
        let png = out.join(precision::FIGURE);
        match precision::draw(&format!("{}: work against precision", cmp.meta.name), &report.precision, &png) {
            Ok(true) => report.precision_figure = Some(png),
            Ok(false) => {
                report.warnings.push(format!("{}: no variant with a cost and an error to draw", png.display()))
            }
            Err(e) => report.warnings.push(format!("{}: cannot draw: {e:#}", png.display())),
        }
    }

    let (header, rows) = report.rows(true);
    let mut w =
        csv::Writer::from_path(&report.table).with_context(|| format!("{}: cannot create", report.table.display()))?;
    w.write_record(&header)?;
    for r in &rows {
        w.write_record(r)?;
    }
    w.flush().with_context(|| format!("{}: cannot write", report.table.display()))?;

    let curves: Vec<(String, &saltus_solvers::Profiles)> = report
        .runs
        .iter()
        .filter_map(|r| {
            let rep = r.report.as_ref()?;
            let label = if r.error.is_some() { format!("{} (failed)", r.name) } else { r.name.clone() };
            Some((label, &rep.profiles))
        })
        .collect();
    if !curves.is_empty() {
        let reference: Vec<Reference> = reference.iter().map(|(label, table)| Reference { label, table }).collect();
        match profiles::draw_profiles(&cmp.meta.name, &COMPARE_PANELS, &curves, &reference, &png) {
            Ok(()) => report.figure = Some(png),
            Err(e) => report.warnings.push(format!("{}: cannot draw: {e:#}", png.display())),
        }
    }
    Ok(report)
}

fn run_variant(cmp: &Comparison, v: &Variant, out: &Path, bars: &MultiProgress) -> VariantRun {
    let dir = out.join(slug(&v.name));
    let mut run =
        VariantRun { name: v.name.clone(), dir: dir.clone(), report: None, error: None, warnings: Vec::new() };
    let sets: Vec<String> = cmp.set.iter().chain(&v.set).cloned().collect();
    // the same checks as `saltus check` and `saltus run`, before any work
    let mut scene = match Scene::from_file_with_closures(&cmp.base, &sets, v.closures.as_deref()) {
        Ok(s) => s,
        Err(e) => {
            run.error = Some(format!("{e}"));
            return run;
        }
    };
    if let Err(e) = saltus_solvers::validate(&scene) {
        run.error = Some(format!("{e}"));
        return run;
    }
    // the variant's own name in its summary.json, scene.toml and figure title
    scene.meta.name = format!("{} [{}]", scene.meta.name, v.name);
    let bar = bars.add(ProgressBar::hidden());
    runner::style_bar(&bar, &v.name);
    let outcome = runner::run_scene(&scene, &dir, &bar, &runner::RunSettings::default());
    bars.remove(&bar);
    run.report = outcome.report;
    run.error = outcome.error.map(|e| e.to_string());
    run.warnings = outcome.warnings;
    run
}
