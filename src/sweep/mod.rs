//! `saltus sweep`: a study over named axes of scene keys, run on this machine
//! ([`run::run`]) or written out as one resolved scene per point for a scheduler
//! ([`emit`]) and gathered afterwards ([`collect`]). See docs/studies.md.
//!
//! ```toml
//! base = "../chassagne2023/case01.toml"   # scene, relative to this file
//! combine = "product"                     # or "zip": the i-th values together
//! set = ['physics.drive="water_depth"']   # overrides of every point
//! unset = ["domain.water_depth"]          # keys of the base removed first
//! [meta]
//! name = "chassagne2023_theta"            # output folder out/<name>
//! [[axis]]
//! key = "physics.shields"                 # any scene key, `seed` for an ensemble
//! name = "theta"                          # column name (default: the key)
//! values = [0.2, 0.4, 0.6]                # or linspace / logspace = [start, stop, count]
//! [[point]]                               # overrides of the points it matches
//! where = { theta = 0.6 }
//! set = ["domain.cells=120"]
//! ```

pub mod figure;
pub mod fit;
pub mod manifest;
pub mod run;
pub mod series;
pub mod spec;
pub mod table;
pub mod warm;

use std::path::{Path, PathBuf};

use anyhow::Context;

pub use manifest::{Manifest, Status};
pub use run::{Options, Report};
pub use spec::{load, Sweep};

/// Output folder when `--out` is not given: `out/<meta.name>`.
pub fn default_out(s: &Sweep) -> PathBuf {
    PathBuf::from("out").join(&s.meta.name)
}

/// Default lower bound of the fitted y (qs*): below it a point is no transport.
pub const FIT_MIN: f64 = 1e-3;

/// Write the sweep's tables and figure from the points' summaries on disk, and return the
/// report.
pub fn finish(
    sweep: &Sweep,
    out: &Path,
    manifest: Manifest,
    mut warnings: Vec<String>,
    ran: usize,
    kept: usize,
) -> anyhow::Result<Report> {
    let summaries: Vec<Option<table::Fields>> =
        manifest.points.iter().map(|p| table::read_summary(&out.join(&p.dir))).collect::<anyhow::Result<_>>()?;
    let mut files = Vec::new();
    let (header, rows) = table::rows(&manifest, &summaries);
    let csv = out.join(table::TABLE);
    table::write_csv(&csv, &header, &rows)?;
    files.push(csv);
    if let Some((h, r)) = table::seed_rows(&manifest, &summaries) {
        let f = out.join(table::SEEDS);
        table::write_csv(&f, &h, &r)?;
        files.push(f);
    }
    let mut fits = Vec::new();
    if let Some((x_desc, y_desc, series)) = series::of(sweep, &manifest, &summaries) {
        let shields =
            x_desc.contains("shields") || sweep.axes.iter().any(|a| a.name == x_desc && a.key == "physics.shields");
        let min = sweep.figure.fit_min.unwrap_or(FIT_MIN);
        if shields {
            for s in &series {
                let fitted: Vec<_> = s.marks.iter().copied().filter(|m| m.1 > min).collect();
                match fit::fit(&fitted) {
                    Ok(f) => fits.push((s.label.clone(), f)),
                    // a series of one or two transporting points has no law to fit
                    Err(_) if fitted.len() < 3 => {}
                    Err(e) => warnings.push(format!("series `{}`: no 3/2 law fitted: {e}", s.label)),
                }
            }
            let f = out.join(series::FITS);
            series::write_fits(&f, &fits)?;
            files.push(f);
        }
        let data = match &sweep.figure.data {
            Some(d) if shields => {
                let path = sweep.file.parent().unwrap_or(Path::new("")).join(d);
                if path.is_file() {
                    figure::read_mpm(&path).unwrap_or_else(|e| {
                        warnings.push(format!("{e:#}; the figure is drawn without the flume data"));
                        Vec::new()
                    })
                } else {
                    warnings.push(format!(
                        "{}: key `figure.data`: {} is not there; the figure is drawn without the flume data",
                        sweep.file.display(),
                        path.display()
                    ));
                    Vec::new()
                }
            }
            _ => Vec::new(),
        };
        let png = out.join(figure::FIGURE);
        let laws: &[_] = if shields { &saltus_solvers::measures::bedload::CLASSIC } else { &[] };
        match figure::draw(&sweep.meta.name, &x_desc, &y_desc, &series, &fits, laws, &data, &png) {
            Ok(()) => files.push(png),
            Err(e) => warnings.push(format!("{}: not drawn: {e:#}", png.display())),
        }
    }
    Ok(Report { out: out.to_path_buf(), manifest, summaries, files, fits, warnings, ran, kept })
}

/// Write one resolved scene per point, `DIR/point_NNNN.toml` (its `output.dir` the
/// point's folder `DIR/point_NNNN`), and the manifest, so that a scheduler's job array
/// runs `saltus run DIR/point_NNNN.toml` and [`collect`] gathers the table.
pub fn emit(sweep: &Sweep, dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let abs = dir.canonicalize().with_context(|| format!("{}: cannot resolve", dir.display()))?;
    let base = sweep.base_table()?;
    let mut hashes = Vec::new();
    let mut files = Vec::new();
    for p in &sweep.points {
        let mut scene = sweep.scene(p, &base)?;
        hashes.push(manifest::hash(scene.to_toml()?.as_bytes()));
        scene.output.dir = Some(abs.join(p.dir_name()).display().to_string());
        let f = dir.join(format!("{}.toml", p.dir_name()));
        let text = format!(
            "# {} point {} ({}), resolved: run with `saltus run {}`\n{}",
            sweep.meta.name,
            p.index,
            sweep.describe(p),
            f.display(),
            scene.to_toml()?
        );
        std::fs::write(&f, text).with_context(|| format!("{}: cannot write", f.display()))?;
        files.push(f);
    }
    Manifest::new(sweep, hashes).write(dir)?;
    Ok(files)
}

/// A point written out for an executor or a scheduler: its resolved scene, its folder,
/// and whether it finished in an earlier run of the same sweep.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// position in the sweep
    pub index: usize,
    /// the resolved scene, `DIR/point_NNNN.toml`
    pub scene: PathBuf,
    /// its output folder, `DIR/point_NNNN`
    pub dir: PathBuf,
    /// `resume` and its summary says it finished: nothing to run
    pub finished: bool,
}

/// [`emit`] for a caller that runs the points itself (the Python `saltus.sweep` with an
/// executor): with `resume`, the folder must hold this sweep (or nothing), and the points
/// whose summaries say they finished are marked so.
pub fn prepare(sweep: &Sweep, dir: &Path, resume: bool) -> anyhow::Result<Vec<Prepared>> {
    if resume && dir.join(manifest::FILE).is_file() {
        let base = sweep.base_table()?;
        let mut hashes = Vec::new();
        for p in &sweep.points {
            hashes.push(manifest::hash(sweep.scene(p, &base)?.to_toml()?.as_bytes()));
        }
        same_sweep(&Manifest::read(dir)?, &Manifest::new(sweep, hashes), sweep, dir, "--resume")?;
    }
    let files = emit(sweep, dir)?;
    let mut out = Vec::with_capacity(files.len());
    for (p, scene) in sweep.points.iter().zip(files) {
        let d = dir.join(p.dir_name());
        let finished = resume && table::read_summary(&d)?.is_some_and(|s| table::status_of(&s).finished());
        out.push(Prepared { index: p.index, scene, dir: d, finished });
    }
    Ok(out)
}

/// Refuse a folder whose manifest `old` is not of the sweep whose fresh manifest is
/// `fresh`, naming the folder, the manifest and the sweep that wrote it.
pub fn same_sweep(old: &Manifest, fresh: &Manifest, sweep: &Sweep, dir: &Path, what: &str) -> anyhow::Result<()> {
    if old.sweep_hash == fresh.sweep_hash {
        return Ok(());
    }
    let differ: Vec<String> = old
        .points
        .iter()
        .zip(&fresh.points)
        .filter(|(a, b)| a.scene_hash != b.scene_hash)
        .map(|(a, _)| a.dir.clone())
        .take(5)
        .collect();
    anyhow::bail!(
        "{what} {}: {} was written by another sweep ({}, {} points){}; {} makes {} points: use the sweep that wrote it, or another folder",
        dir.display(),
        dir.join(manifest::FILE).display(),
        old.sweep.display(),
        old.points.len(),
        if differ.is_empty() { String::new() } else { format!(", whose scenes differ at {}", differ.join(", ")) },
        sweep.file.display(),
        fresh.points.len()
    )
}

/// Gather the points of the sweep emitted into `dir` (or run there): each point's status
/// from its `summary.json`, then the tables and the figure as [`run::run`] writes them.
pub fn collect(sweep: &Sweep, dir: &Path) -> anyhow::Result<Report> {
    let base = sweep.base_table()?;
    let mut hashes = Vec::new();
    for p in &sweep.points {
        hashes.push(manifest::hash(sweep.scene(p, &base)?.to_toml()?.as_bytes()));
    }
    let fresh = Manifest::new(sweep, hashes);
    let old = Manifest::read(dir)?;
    same_sweep(&old, &fresh, sweep, dir, "--collect")?;
    let mut m = old;
    for p in &mut m.points {
        match table::read_summary(&dir.join(&p.dir))? {
            Some(s) => {
                p.status = table::status_of(&s);
                p.ending = s.text("ending").map(str::to_string);
                p.wall_time_s = s.number("wall_time_s");
                p.cpu_time_s = s.number("cpu_time_s");
                p.error = s.text("error").map(str::to_string);
            }
            None => p.status = Status::Pending,
        }
    }
    m.write(dir)?;
    let kept = m.points.iter().filter(|p| p.status.finished()).count();
    finish(sweep, dir, m, Vec::new(), 0, kept)
}
