//! `saltus run`: one scene through its solver, with a progress bar on a terminal and the
//! profile figure `profiles.png` next to the solver's outputs. Also used by
//! `saltus compare` for each variant.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

use anyhow::{bail, Context};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use saltus_core::scene::Scene;
use saltus_solvers::{Profiles, Progress, RunReport, Summary};
use serde::Deserialize;

use crate::plot::{self, Reference, RUN_PANELS};
use crate::table::Table;

/// File name of the profile figure written next to the solver's outputs.
pub const FIGURE: &str = "profiles.png";

/// What a run left behind.
#[derive(Debug)]
pub struct RunOutcome {
    /// profiles and summary: the solver's report, or after a failed (unstable) run the
    /// last good state the solver wrote, read back (with an empty `text`); `None` when
    /// the solver failed before writing anything
    pub report: Option<RunReport>,
    /// the solver's error, if it failed
    pub error: Option<saltus_core::Error>,
    /// the profile figure, when drawn
    pub figure: Option<PathBuf>,
    /// things the user should know that did not fail the run (missing reference data, a
    /// figure that could not be drawn)
    pub warnings: Vec<String>,
}

/// A progress bar over simulated time, drawn on stderr when `visible`, hidden otherwise.
pub fn progress_bar(visible: bool) -> ProgressBar {
    let target = if visible { ProgressDrawTarget::stderr() } else { ProgressDrawTarget::hidden() };
    let bar = ProgressBar::with_draw_target(None, target);
    style_bar(&bar, "");
    bar
}

/// Style `bar` as a run's progress bar; `prefix` goes before it (a variant name in
/// `saltus compare`).
pub fn style_bar(bar: &ProgressBar, prefix: &str) {
    let template = if prefix.is_empty() {
        "[{elapsed_precise}] {bar:30.cyan/blue} {msg}"
    } else {
        "{prefix:>24.bold} [{elapsed_precise}] {bar:30.cyan/blue} {msg}"
    };
    let style = ProgressStyle::with_template(template).expect("valid progress template").progress_chars("=> ");
    bar.set_style(style);
    bar.set_prefix(prefix.to_string());
}

/// Positions of the progress bar per simulated second.
const TICKS_PER_SECOND: f64 = 1000.0;

/// Run `scene` into `out`, showing progress on `bar` (see [`progress_bar`]), then draw
/// `profiles.png` in `out`, also after an unstable run (from the last good state the
/// solver wrote). Reference data that cannot be read gives a warning, not a failure.
pub fn run_scene(scene: &Scene, out: &Path, bar: &ProgressBar) -> RunOutcome {
    let mut last: Option<Instant> = None;
    let mut observer = |p: &Progress| {
        if !matches!(last, Some(t) if t.elapsed() < Duration::from_millis(50)) {
            last = Some(Instant::now());
            bar.set_length((p.end_time * TICKS_PER_SECOND) as u64);
            bar.set_position((p.time * TICKS_PER_SECOND) as u64);
            bar.set_message(format!(
                "t = {:.3} / {:.0} s  step {}  dt = {:.2e} s  residual {:.2e} /s",
                p.time, p.end_time, p.steps, p.dt, p.residual
            ));
        }
        true
    };
    let started = SystemTime::now();
    let result = saltus_solvers::run(scene, out, &mut observer);
    bar.finish_and_clear();
    let mut warnings = Vec::new();
    let (report, error) = match result {
        Ok(r) => (Some(r), None),
        Err(e) => (last_good_state(out, started), Some(e)),
    };
    let figure = report.as_ref().and_then(|r| {
        let png = out.join(FIGURE);
        match draw_run(scene, r, error.is_some(), &png, &mut warnings) {
            Ok(()) => Some(png),
            Err(e) => {
                warnings.push(format!("{}: cannot draw: {e:#}", png.display()));
                None
            }
        }
    });
    RunOutcome { report, error, figure, warnings }
}

fn draw_run(scene: &Scene, r: &RunReport, failed: bool, png: &Path, warnings: &mut Vec<String>) -> anyhow::Result<()> {
    let reference = match load_reference(scene) {
        Ok(r) => r,
        Err(e) => {
            warnings.push(format!("{e:#}; {} drawn without reference data", png.display()));
            Vec::new()
        }
    };
    let s = &r.summary;
    let name = if scene.meta.name.is_empty() { "run" } else { scene.meta.name.as_str() };
    let title = if failed {
        format!("{name}: stopped ({}) at t = {:.3} s, last good state", s.ending, s.sim_time_s)
    } else {
        format!("{name}: {} at t = {:.1} s, qs* = {:.3}, Shields {:.3}", s.ending, s.sim_time_s, s.qs_star, s.shields)
    };
    let reference: Vec<Reference> = reference.iter().map(|(label, table)| Reference { label, table }).collect();
    plot::draw_profiles(&title, &RUN_PANELS, &[(name.to_string(), &r.profiles)], &reference, png)
}

/// After a failed run: the summary and profiles the solver wrote into `out` during this
/// run (written at or after `started`, and ending as unstable), or `None`.
fn last_good_state(out: &Path, started: SystemTime) -> Option<RunReport> {
    let summary_path = out.join("summary.json");
    // coarse file-system clocks may stamp a fresh file slightly before `started`
    let fresh = std::fs::metadata(&summary_path)
        .and_then(|m| m.modified())
        .is_ok_and(|t| t + Duration::from_secs(1) >= started);
    if !fresh {
        return None;
    }
    let summary = read_summary(&summary_path).ok()?;
    if summary.ending != "unstable" {
        return None;
    }
    let profiles = read_profiles(&out.join("profiles.csv")).ok()?;
    Some(RunReport { profiles, summary, text: String::new() })
}

/// Read a `summary.json` written by a solver. JSON has no NaN: serde_json writes a NaN
/// number (the bed height of a run without transport, say) as `null`, which `Summary`
/// does not read back; such nulls are read as NaN here.
pub fn read_summary(path: &Path) -> anyhow::Result<Summary> {
    fn nan_for_null(v: serde_json::Value) -> toml::Value {
        use serde_json::Value as J;
        match v {
            J::Null => toml::Value::Float(f64::NAN),
            J::Bool(b) => toml::Value::Boolean(b),
            J::Number(n) => match n.as_i64() {
                Some(i) => toml::Value::Integer(i),
                None => toml::Value::Float(n.as_f64().unwrap_or(f64::NAN)),
            },
            J::String(s) => toml::Value::String(s),
            J::Array(a) => toml::Value::Array(a.into_iter().map(nan_for_null).collect()),
            J::Object(o) => toml::Value::Table(o.into_iter().map(|(k, v)| (k, nan_for_null(v))).collect()),
        }
    }
    let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let json: serde_json::Value = serde_json::from_str(&text).with_context(|| format!("{}", path.display()))?;
    Summary::deserialize(nan_for_null(json)).with_context(|| format!("{}", path.display()))
}

/// Read a `profiles.csv` written by a solver (header line, then numbers; NaN and inf
/// allowed, since a failing run may leave them).
pub fn read_profiles(path: &Path) -> anyhow::Result<Profiles> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let mut lines = text.lines();
    let names: Vec<&str> = lines.next().unwrap_or("").split(',').map(str::trim).collect();
    let mut columns = vec![Vec::new(); names.len()];
    for (i, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            bail!("{}: row {} has {} cells, the header has {}", path.display(), i + 2, cells.len(), names.len());
        }
        for (c, cell) in columns.iter_mut().zip(cells) {
            c.push(cell.parse::<f64>().with_context(|| format!("{}: row {}: `{cell}`", path.display(), i + 2))?);
        }
    }
    let mut p = Profiles::default();
    for (n, c) in names.into_iter().zip(columns) {
        p.push(n, c);
    }
    Ok(p)
}

/// The scene's reference data (`[reference]` or `[[reference]]`): per file a legend label
/// (the file stem) and its columns, `z` shifted by the entry's `z_offset`; empty when the
/// scene has none. Errors name the scene, the key and the resolved file.
pub fn load_reference(scene: &Scene) -> anyhow::Result<Vec<(String, Table)>> {
    let dir = scene.path.parent().unwrap_or(Path::new(""));
    let many = scene.reference.len() > 1;
    let mut out = Vec::with_capacity(scene.reference.len());
    for (i, r) in scene.reference.iter().enumerate() {
        let key = if many { format!("reference[{i}]") } else { "reference".into() };
        let file = dir.join(&r.file);
        let mut table =
            read_columns(&file, &r.columns).with_context(|| format!("{}: key `{key}.file`", scene.path.display()))?;
        if r.z_offset != 0.0 {
            if !r.z_offset.is_finite() {
                bail!("{}: key `{key}.z_offset` = {}: must be a finite length in m", scene.path.display(), r.z_offset);
            }
            match table.column_mut("z") {
                Some(z) => z.iter_mut().for_each(|z| *z += r.z_offset),
                None => bail!("{}: key `{key}.z_offset`: the file has no `z` column to shift", scene.path.display()),
            }
        }
        let label = file.file_stem().map_or_else(|| "reference".into(), |n| n.to_string_lossy().into_owned());
        out.push((label, table));
    }
    Ok(out)
}

/// Read a file of numeric columns separated by whitespace or commas, `#` comment lines
/// and blank lines skipped, naming the columns `names` in order.
pub fn read_columns(path: &Path, names: &[String]) -> anyhow::Result<Table> {
    let origin = path.display();
    if names.is_empty() {
        bail!("{origin}: `reference.columns` names no column");
    }
    let text = std::fs::read_to_string(path).with_context(|| format!("{origin}: cannot read"))?;
    let mut columns = vec![Vec::new(); names.len()];
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split(|c: char| c.is_whitespace() || c == ',').filter(|c| !c.is_empty()).collect();
        if cells.len() != names.len() {
            bail!(
                "{origin}:{}: {} values, but `reference.columns` names {} ({})",
                i + 1,
                cells.len(),
                names.len(),
                names.join(", ")
            );
        }
        for ((c, cell), name) in columns.iter_mut().zip(cells).zip(names) {
            let v: f64 = cell
                .parse()
                .map_err(|_| anyhow::anyhow!("{origin}:{}: column `{name}`: `{cell}` is not a number", i + 1))?;
            c.push(v);
        }
    }
    if columns[0].is_empty() {
        bail!("{origin}: no data rows");
    }
    let mut t = Table::default();
    for (n, c) in names.iter().zip(columns) {
        t.push(n.clone(), c);
    }
    Ok(t)
}

/// Output folder of a scene: its `output.dir`, else `out/<meta.name>`, else
/// `out/<file stem>`.
pub fn default_out(s: &Scene) -> PathBuf {
    match &s.output.dir {
        Some(d) => PathBuf::from(d),
        None => {
            let name = if s.meta.name.is_empty() {
                s.path.file_stem().map_or_else(|| "run".into(), |x| x.to_string_lossy().into_owned())
            } else {
                s.meta.name.clone()
            };
            PathBuf::from("out").join(name)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_split_on_whitespace_and_commas_and_skip_comments() {
        let d = std::env::temp_dir().join(format!("saltus_runner_{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let f = d.join("ref.txt");
        std::fs::write(&f, "# z phi\n0.0 0.6\n\n0.1, 0.5\n0.2\t,0.0\n").unwrap();
        let t = read_columns(&f, &["z".into(), "phi".into()]).unwrap();
        assert_eq!(t.get("z").unwrap(), &[0.0, 0.1, 0.2]);
        assert_eq!(t.get("phi").unwrap(), &[0.6, 0.5, 0.0]);
        std::fs::write(&f, "0.0 0.6 1.0\n").unwrap();
        let e = read_columns(&f, &["z".into(), "phi".into()]).unwrap_err().to_string();
        assert!(e.contains("ref.txt:1") && e.contains("3 values"), "{e}");
        std::fs::write(&f, "0.0 abc\n").unwrap();
        let e = read_columns(&f, &["z".into(), "phi".into()]).unwrap_err().to_string();
        assert!(e.contains("`phi`") && e.contains("abc"), "{e}");
        let _ = std::fs::remove_dir_all(&d);
    }
}
