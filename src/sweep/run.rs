//! Running a sweep on this machine: its points in parallel, each in a folder of its own,
//! the manifest rewritten after every point, `--resume` keeping the finished ones.
//!
//! Each worker thread runs its points inside a rayon pool of one thread, so that a DEM
//! point whose `solver.lagrangian.threads` is 0 (the caller's pool) runs on one core, the
//! CPU time of the worker is the point's, and `jobs` workers keep `jobs` cores busy.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

use anyhow::{bail, Context};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::manifest::{hash, Manifest, Status};
use super::spec::Sweep;
use super::table::{self, Fields};
use super::warm;
use crate::runner;

/// How a sweep runs.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// continue the sweep in the folder: keep its finished points
    pub resume: bool,
    /// points run at once (default: the sweep file's `jobs`, else the cores)
    pub jobs: Option<usize>,
    /// one progress bar over all points on stderr (else a line per finished point)
    pub progress: bool,
    /// print nothing while running
    pub quiet: bool,
}

/// What a sweep left behind.
#[derive(Debug)]
pub struct Report {
    /// the sweep's folder
    pub out: PathBuf,
    /// the manifest as written
    pub manifest: Manifest,
    /// each point's summary (`None`: it has none)
    pub summaries: Vec<Option<Fields>>,
    /// `sweep.csv`, `sweep_seeds.csv` (with a seed axis), the figure
    pub files: Vec<PathBuf>,
    /// the 3/2-law fit of each series of the figure (its label, the fit)
    pub fits: Vec<(String, super::fit::Fit)>,
    /// what did not fail the sweep but should be known
    pub warnings: Vec<String>,
    /// points run now
    pub ran: usize,
    /// points kept from an earlier run
    pub kept: usize,
}

impl Report {
    /// Points that did not end done.
    pub fn failures(&self) -> usize {
        self.manifest.points.iter().filter(|p| p.status != Status::Done).count()
    }
}

/// The manifest of `sweep` in `out` to continue from: the one there, checked to be this
/// sweep's, or a fresh one.
fn starting_manifest(sweep: &Sweep, out: &Path, fresh: Manifest, resume: bool) -> anyhow::Result<Manifest> {
    let file = out.join(super::manifest::FILE);
    if !resume {
        return Ok(fresh);
    }
    if !file.is_file() {
        let busy = std::fs::read_dir(out).map(|mut d| d.next().is_some()).unwrap_or(false);
        if busy {
            bail!(
                "--resume {}: the folder holds no {} (not a sweep's folder); give the folder the sweep wrote",
                out.display(),
                super::manifest::FILE
            );
        }
        return Ok(fresh);
    }
    let old = Manifest::read(out)?;
    super::same_sweep(&old, &fresh, sweep, out, "--resume")?;
    let mut m = fresh;
    for (new, old) in m.points.iter_mut().zip(old.points) {
        // a finished point is kept only with its summary on disk
        if old.status.finished() && out.join(&old.dir).join(crate::run_files::SUMMARY).is_file() {
            *new = old;
        } else if old.status == Status::Interrupted {
            // it continues from its checkpoint, from the start it was given
            new.status = Status::Interrupted;
            new.warm_start_from = old.warm_start_from;
            new.warm_start_refused = old.warm_start_refused;
        }
    }
    Ok(m)
}

/// Run `sweep` into `out`: every point not finished (all of them unless `resume`), then
/// `sweep.csv`, `sweep_seeds.csv` with a seed axis, and the figure. An interrupt stops
/// the running points with their state written (a DEM point with its checkpoint, from
/// which `--resume` continues it) and starts no other.
pub fn run(sweep: &Sweep, out: &Path, opts: &Options) -> anyhow::Result<Report> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let base = sweep.base_table()?;
    let mut hashes = Vec::with_capacity(sweep.points.len());
    let mut warm = Vec::with_capacity(sweep.points.len());
    for p in &sweep.points {
        let s = sweep.scene(p, &base)?;
        hashes.push(hash(s.to_toml()?.as_bytes()));
        warm.push(warm::can_start_warm(&s));
    }
    let manifest = starting_manifest(sweep, out, Manifest::new(sweep, hashes), opts.resume)?;
    let kept = manifest.points.iter().filter(|p| p.status.finished()).count();
    manifest.write(out)?;
    let todo: VecDeque<usize> = manifest.points.iter().filter(|p| !p.status.finished()).map(|p| p.index).collect();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let jobs = opts.jobs.or(sweep.jobs).unwrap_or(cores).clamp(1, todo.len().max(1));
    let bar = if opts.progress && !opts.quiet {
        ProgressBar::with_draw_target(Some(sweep.points.len() as u64), ProgressDrawTarget::stderr())
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("[{elapsed_precise}] {bar:30.cyan/blue} {pos}/{len} points {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_position((sweep.points.len() - todo.len()) as u64);
    let shared = Mutex::new(Shared { manifest, todo, warnings: Vec::new(), ran: 0 });
    let chains = warm::Chains::new(sweep);
    let ctx = Work { sweep, out, base: &base, warm: &warm, chains: &chains, bar: &bar, opts };
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| worker(&ctx, &shared));
        }
    });
    bar.finish_and_clear();
    let Shared { manifest, warnings, ran, .. } = shared.into_inner().unwrap_or_else(|e| e.into_inner());
    manifest.write(out)?;
    super::finish(sweep, out, manifest, warnings, ran, kept)
}

struct Shared {
    manifest: Manifest,
    todo: VecDeque<usize>,
    warnings: Vec<String>,
    /// points started
    ran: usize,
}

/// What every worker reads.
struct Work<'a> {
    sweep: &'a Sweep,
    out: &'a Path,
    base: &'a toml::Table,
    /// per point, whether its scene can start warm
    warm: &'a [bool],
    chains: &'a warm::Chains,
    bar: &'a ProgressBar,
    opts: &'a Options,
}

/// Wall time a worker waits before looking again for a point whose parent has finished.
const WAIT: std::time::Duration = std::time::Duration::from_millis(5);

fn worker(ctx: &Work, shared: &Mutex<Shared>) {
    let Work { sweep, out, base, warm, chains, bar, opts } = *ctx;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build();
    loop {
        if runner::interrupted() {
            return;
        }
        let (i, restart, warm_from) = {
            let mut s = shared.lock().unwrap_or_else(|e| e.into_inner());
            if s.todo.is_empty() {
                return;
            }
            // the next point whose parent (a warm start's) is settled
            let ready = s.todo.iter().position(|&i| {
                chains
                    .parent(i)
                    .is_none_or(|p| !matches!(s.manifest.points[p].status, Status::Pending | Status::Running))
            });
            let Some(k) = ready else {
                drop(s);
                std::thread::sleep(WAIT);
                continue;
            };
            let Some(i) = s.todo.remove(k) else { return };
            s.ran += 1;
            let entry = &mut s.manifest.points[i];
            let dir = out.join(&entry.dir);
            // an interrupted DEM point continues from its checkpoint
            let restart = (entry.status == Status::Interrupted
                && dir.join(saltus_solvers::run::checkpoint::FILE).is_file())
            .then_some(dir);
            entry.status = Status::Running;
            let warm_from = chains
                .parent(i)
                .filter(|&p| warm[i] && restart.is_none() && s.manifest.points[p].status == Status::Done)
                .map(|p| s.manifest.points[p].dir.clone());
            let _ = s.manifest.write(out);
            (i, restart, warm_from)
        };
        let p = &sweep.points[i];
        let dir = out.join(p.dir_name());
        // a continued point keeps the start it was given when it began
        let continued = restart.is_some();
        bar.set_message(format!("running {} ({})", p.dir_name(), sweep.describe(p)));
        let job = || {
            let cpu0 = saltus_solvers::run::cpu::thread_seconds();
            let started = Instant::now();
            let result = run_point(sweep, p, base, &dir, restart, warm_from.as_ref().map(|w| out.join(w)));
            let cpu = saltus_solvers::run::cpu::thread_seconds().zip(cpu0).map(|(b, a)| b - a);
            (result, cpu, started.elapsed().as_secs_f64())
        };
        let (result, cpu, wall) = match &pool {
            Ok(pool) => pool.install(job),
            Err(_) => job(),
        };
        let mut s = shared.lock().unwrap_or_else(|e| e.into_inner());
        let entry = &mut s.manifest.points[i];
        // a DEM point runs on its own pool, whose threads this one's clock does not see:
        // the summary's CPU time counts them; a continued point adds what it cost before
        let cpu = result.as_ref().ok().and_then(|r| r.cpu_time_s).or(cpu);
        let before = |t: Option<f64>| if continued { t.unwrap_or(0.0) } else { 0.0 };
        entry.cpu_time_s = cpu.map(|c| c + before(entry.cpu_time_s));
        entry.wall_time_s = Some(wall + before(entry.wall_time_s));
        if !continued {
            entry.warm_start_from = warm_from.clone();
            entry.warm_start_refused = None;
        }
        let line;
        match result {
            Ok(PointResult { status, ending, error, warnings, refused, .. }) => {
                if refused.is_some() {
                    // started from rest: it did not start from the parent
                    entry.warm_start_from = None;
                    entry.warm_start_refused.clone_from(&refused);
                }
                entry.status = status;
                entry.ending = ending;
                entry.error = error;
                line = format!(
                    "{} ({}): {}{}{}",
                    entry.dir,
                    sweep.describe(p),
                    entry.ending.as_deref().unwrap_or("-"),
                    entry.error.as_ref().map_or_else(String::new, |e| format!(": {e}")),
                    refused.map_or_else(String::new, |why| format!(" (from rest, warm start refused: {why})"))
                );
                for w in warnings {
                    if !s.warnings.contains(&w) {
                        s.warnings.push(w);
                    }
                }
            }
            Err(e) => {
                entry.status = Status::Failed;
                entry.error = Some(format!("{e:#}"));
                line = format!("{} ({}): failed: {e:#}", entry.dir, sweep.describe(p));
            }
        }
        if let Err(e) = s.manifest.write(out) {
            let w = format!("{e:#}");
            if !s.warnings.contains(&w) {
                s.warnings.push(w);
            }
        }
        drop(s);
        bar.inc(1);
        if bar.is_hidden() && !opts.quiet {
            crate::errln!("{line} [{wall:.2} s]");
        }
    }
}

/// How a point's run ended.
struct PointResult {
    status: Status,
    /// the ending's name (`steady`, `end_time`, `unstable`, ...)
    ending: Option<String>,
    error: Option<String>,
    warnings: Vec<String>,
    /// why the point started from rest when its warm start was refused
    refused: Option<String>,
    /// the run's CPU time from its summary, its solver's own threads counted
    cpu_time_s: Option<f64>,
}

fn run_point(
    sweep: &Sweep,
    p: &super::spec::Point,
    base: &toml::Table,
    dir: &Path,
    restart: Option<PathBuf>,
    warm_from: Option<PathBuf>,
) -> anyhow::Result<PointResult> {
    let scene = sweep.scene(p, base)?;
    let settings = runner::RunSettings { restart, log_every: None, max_wall: None, warm_start: None };
    let bar = ProgressBar::hidden();
    let mut stop = |_: &saltus_solvers::Progress| runner::interrupted();
    let (outcome, refused) = match &warm_from {
        Some(from) => warm::run_from(&scene, dir, from, &mut stop)?,
        None => (runner::run_scene_with(&scene, dir, &bar, &settings, &mut stop)?, None),
    };
    let status = match (&outcome.ending, &outcome.error) {
        (Some(saltus_solvers::Ending::Unstable(_)), _) => Status::Unstable,
        (Some(saltus_solvers::Ending::Interrupted), _) => Status::Interrupted,
        (Some(_), None) => Status::Done,
        _ => Status::Failed,
    };
    let ending = outcome.ending.as_ref().map(|e| e.name().to_string());
    // the run's own CPU time: its solver's threads as well as the calling one (a run that
    // failed may have left the summary of an earlier run in its folder)
    let summary = table::read_summary(dir)?;
    let cpu = summary.filter(|_| status != Status::Failed).and_then(|s| s.number("cpu_time_s"));
    Ok(PointResult { status, ending, error: outcome.error, warnings: outcome.warnings, refused, cpu_time_s: cpu })
}

impl Report {
    /// The points as aligned text: axes, status, qs* (with its error), and the fit.
    pub fn text(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let m = &self.manifest;
        let _ = writeln!(
            s,
            "{}: {} points ({} run now, {} kept), {} done",
            m.name,
            m.points.len(),
            self.ran,
            self.kept,
            m.points.iter().filter(|p| p.status == Status::Done).count()
        );
        for (p, sm) in m.points.iter().zip(&self.summaries) {
            let values: Vec<String> = m
                .axes
                .iter()
                .map(|a| {
                    let k = a.values.iter().position(|v| Some(v) == p.values.get(&a.name));
                    format!("{} = {}", a.name, k.map_or("?", |k| a.labels[k].as_str()))
                })
                .collect();
            let q = sm.as_ref().and_then(|s| s.number("qs_star"));
            let e = sm.as_ref().and_then(|s| s.number("qs_star_stderr"));
            let q = match (q, e) {
                (Some(q), Some(e)) => format!("qs* = {q:.4} +- {e:.4}"),
                (Some(q), None) => format!("qs* = {q:.6}"),
                _ => "qs* -".into(),
            };
            let st =
                serde_json::to_value(p.status).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
            let _ = writeln!(s, "  {}  {}  {st:<11}  {q}", p.dir, values.join(", "));
        }
        for (label, f) in &self.fits {
            let of = if label.is_empty() { String::new() } else { format!(" ({label})") };
            let _ = writeln!(
                s,
                "3/2-law fit{of} over {} points: qs* = {:.4} (+- {:.4}) (theta - {:.5} (+- {:.5}))^1.5, rms {:.3e}",
                f.n, f.a, f.a_stderr, f.theta_c, f.theta_c_stderr, f.rms
            );
            if f.at_bound {
                let _ = writeln!(
                    s,
                    "  theta_c is at the smallest fitted value: the points rise faster than a 3/2 power above any one threshold"
                );
            }
            if f.n_stand_in > 0 {
                let _ = writeln!(
                    s,
                    "  {} of the points have no error of their own and weigh as the least certain of the others",
                    f.n_stand_in
                );
            }
        }
        s
    }
}
