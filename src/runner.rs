//! `saltus run`: one scene through its solver, with a progress bar on a terminal and the
//! profile figure `profiles.png` next to the solver's outputs. Also used by
//! `saltus compare` for each variant.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::{bail, Context};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use saltus_core::param::decimal;
use saltus_core::scene::Scene;
use saltus_solvers::run::{Clock, Control, Phase};
use saltus_solvers::{Ending, Observer, Progress, RunReport, Stepper};

use crate::figures::profiles::{draw_profiles, Reference, RUN_PANELS};
use crate::run_files;
use crate::table::Table;

/// File name of the profile figure written next to the solver's outputs.
pub const FIGURE: &str = "profiles.png";

/// Exit code of bad input (scene, overrides, `--restart`) or outputs that cannot be
/// written.
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit code of a run that went unstable (its last good state is written).
pub const EXIT_UNSTABLE: u8 = 3;
/// Exit code of a run stopped by Ctrl-C, SIGINT or SIGTERM (its state at that time is
/// written, with a checkpoint for the DEM), as a shell reports a process ended by SIGINT.
pub const EXIT_INTERRUPTED: u8 = 130;

/// Default wall time between two progress lines when stderr is no terminal (s).
pub const LOG_INTERVAL: f64 = 30.0;

/// How `saltus run` (and each variant of `saltus compare`) runs and tells its progress.
#[derive(Clone, Debug)]
pub struct RunSettings {
    /// continue from the checkpoint in this folder (`--restart`)
    pub restart: Option<PathBuf>,
    /// wall time between two progress lines on a hidden bar; `None`: no lines (`--quiet`)
    pub log_every: Option<Duration>,
    /// stop the run after this many wall-clock seconds (`--max-wall`)
    pub max_wall: Option<f64>,
    /// start from another run's final state (a sweep's warm start) instead of the
    /// initial state
    pub warm_start: Option<saltus_solvers::WarmStart>,
}

impl Default for RunSettings {
    fn default() -> Self {
        Self { restart: None, log_every: Some(Duration::from_secs_f64(LOG_INTERVAL)), max_wall: None, warm_start: None }
    }
}

/// What a run left behind.
#[derive(Debug)]
pub struct RunOutcome {
    /// how the run ended; `None` when it could not be set up or its outputs not written
    pub ending: Option<Ending>,
    /// profiles, summary and paragraph of the last state, as the solver returned them
    /// (also after a breakdown or an interruption); `None` with `ending`
    pub report: Option<RunReport>,
    /// why the run failed or stopped early (set-up or write error, breakdown,
    /// interruption)
    pub error: Option<String>,
    /// the profile figure, when drawn
    pub figure: Option<PathBuf>,
    /// the phase-average figures (`phases.png`, `phase_profiles.png`) of a run under a
    /// periodic forcing; empty otherwise
    pub phase_figures: Vec<PathBuf>,
    /// things the user should know that did not fail the run (missing reference data, a
    /// figure that could not be drawn)
    pub warnings: Vec<String>,
    /// wall-clock time of the solve (s); 0 when the run could not be set up
    pub wall: f64,
}

impl RunOutcome {
    /// A run that could not be set up or whose outputs could not be written.
    pub fn failed(error: String) -> Self {
        Self {
            ending: None,
            report: None,
            error: Some(error),
            figure: None,
            phase_figures: Vec::new(),
            warnings: Vec::new(),
            wall: 0.0,
        }
    }
}

/// A run that ended early but wrote its outputs: the message and the exit code.
#[derive(Debug)]
pub struct Stopped {
    /// [`EXIT_UNSTABLE`] or [`EXIT_INTERRUPTED`]
    pub code: u8,
    /// what happened and where the outputs are
    pub message: String,
}

impl fmt::Display for Stopped {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Stopped {}

impl RunOutcome {
    /// The early stop of this run, for the exit code; `None` when it ran to its end or
    /// failed before running.
    pub fn stopped(&self, scene: &Scene, out: &Path) -> Option<Stopped> {
        let (ending, report) = (self.ending.as_ref()?, self.report.as_ref()?);
        let t = report.summary.sim_time_s;
        let drawn = self.figure.as_ref().map_or_else(String::new, |p| format!("; drawn in {}", p.display()));
        let file = scene.path.display();
        match ending {
            Ending::Unstable(b) => Some(Stopped {
                code: EXIT_UNSTABLE,
                message: format!(
                    "{file}: run stopped, unstable at {b}; the last good state (t = {} s) is written to {}{drawn}",
                    decimal(t),
                    out.display()
                ),
            }),
            Ending::Interrupted => {
                let resume = if out.join(saltus_solvers::run::checkpoint::FILE).is_file() {
                    format!(
                        "; continue with `saltus run {file} --restart {}` (and the same --set options)",
                        out.display()
                    )
                } else {
                    String::new()
                };
                Some(Stopped {
                    code: EXIT_INTERRUPTED,
                    message: format!(
                        "{file}: interrupted at t = {} s of flow; the state at that time is written to {}{drawn}{resume}",
                        decimal(t),
                        out.display()
                    ),
                })
            }
            Ending::Steady | Ending::EndTime | Ending::TargetError | Ending::MaxSteps | Ending::WallClock => None,
        }
    }
}

/// Set by Ctrl-C, SIGINT or SIGTERM: runs in progress stop after their current unit of
/// work.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Catch Ctrl-C, SIGINT, SIGTERM (a batch system's time limit) and SIGHUP: the first one
/// stops the runs in progress through their observer (each writes its outputs, ending
/// `interrupted`, and the DEM a checkpoint), a second one quits at once with
/// [`EXIT_INTERRUPTED`]. Call once per process.
pub fn catch_interrupt() -> anyhow::Result<()> {
    ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::SeqCst) {
            std::process::exit(EXIT_INTERRUPTED.into());
        }
        crate::errln!(
            "\ninterrupted: stopping after the current step and writing the outputs (interrupt again to quit at once)"
        );
    })
    .context("cannot catch Ctrl-C and SIGTERM")
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::SeqCst)
}

/// A progress bar over simulated time, drawn on stderr when `visible`, hidden otherwise
/// (then [`run_scene`] prints a progress line every [`RunSettings::log_every`] instead).
pub fn progress_bar(visible: bool) -> ProgressBar {
    let target = if visible { ProgressDrawTarget::stderr() } else { ProgressDrawTarget::hidden() };
    let bar = ProgressBar::with_draw_target(None, target);
    style_bar(&bar, "");
    bar
}

/// Style `bar` as a run's progress bar; `prefix` goes before it (a variant name in
/// `saltus compare`). Until the run reports its first progress, the bar is a line that
/// says it is being set up (no empty bar).
pub fn style_bar(bar: &ProgressBar, prefix: &str) {
    bar.set_prefix(prefix.to_string());
    bar.set_style(template(prefix, "[{elapsed_precise}] {msg}"));
    bar.set_message("setting up");
}

fn template(prefix: &str, body: &str) -> ProgressStyle {
    let t = if prefix.is_empty() { body.to_string() } else { format!("{{prefix:>24.bold}} {body}") };
    // the templates are constants of this file: a bad one is a bug, drawn as plain text
    ProgressStyle::with_template(&t).unwrap_or_else(|_| ProgressStyle::default_bar()).progress_chars("=> ")
}

/// Positions of the progress bar per simulated second.
const TICKS_PER_SECOND: f64 = 1000.0;

/// Name of a phase in the progress.
pub fn phase_name(phase: Phase) -> &'static str {
    match phase {
        Phase::Setup => "deposition",
        Phase::Flow => "flow",
    }
}

/// One line of progress: phase, time, step, time step and, once there is one, the
/// residual.
pub fn describe(p: &Progress) -> String {
    let mut s = format!(
        "{} t = {:.3} / {:.3} s  step {}  dt = {:.2e} s",
        phase_name(p.phase),
        p.time,
        p.end_time,
        p.steps,
        p.dt
    );
    if let Some(r) = p.residual {
        s.push_str(&format!("  residual {r:.2e}"));
    }
    s
}

/// Wall time left in the phase at its pace so far (s): `None` before any progress. The
/// pace counts from `t0`, the simulated time at which this run entered the phase (a
/// restart enters the flow at its checkpoint's time, not at 0).
fn eta(p: &Progress, phase_wall: f64, t0: f64) -> Option<f64> {
    let (left, done) = ((p.end_time - p.time).max(0.0), p.time - t0);
    (done > 0.0 && phase_wall > 0.0).then(|| left * phase_wall / done).filter(|e| e.is_finite())
}

/// Load a scene and check it whole: the schema with the `--set KEY=VALUE` overrides
/// applied, then what its solver needs to start (the set-up a run does before any work).
/// `saltus check` and the Python `saltus.check` call it, so they refuse what `run` would.
/// `closures`: a closures file whose tables replace the scene's (`--closures FILE`).
pub fn load_checked(scene: &Path, set: &[String], closures: Option<&Path>) -> Result<Scene, saltus_core::Error> {
    let s = Scene::from_file_with_closures(scene, set, closures)?;
    saltus_solvers::validate(&s)?;
    // a closure registered at run time that failed while the solver was being set up
    match s.closures.failure() {
        Some(f) => Err(saltus_core::Error::Invalid(format!("{}: {f}", scene.display()))),
        None => Ok(s),
    }
}

/// The final profiles a run wrote into `dir`.
pub fn profiles(dir: &Path) -> anyhow::Result<saltus_solvers::Profiles> {
    run_files::profiles(dir).with_context(|| format!("{}: no profiles to start from", dir.display()))
}

/// The final state of the run in `from` that `scene` starts from (a sweep's warm start,
/// `saltus run --warm-start`): its profiles for the Eulerian column; for the DEM, the
/// grains of its checkpoint, or the velocities of its profiles when `from` is a run of the
/// Eulerian solver (its `summary.json` says so). `Err` when `from` holds no such state;
/// `Ok(Err)` with the reason when the DEM scene cannot take the checkpoint's grains.
pub fn warm_state(scene: &Scene, from: &Path) -> anyhow::Result<Result<saltus_solvers::WarmStart, String>> {
    use saltus_core::scene::SolverKind;
    use saltus_solvers::WarmStart;
    if !from.is_dir() {
        bail!("{}: not a run folder", from.display());
    }
    let two_fluid = || {
        let v: serde_json::Value = run_files::summary(from).ok()??;
        Some(v.get("solver")?.as_str()? == "eulerian")
    };
    match scene.solver.kind {
        SolverKind::Eulerian => Ok(Ok(WarmStart::Profiles(profiles(from)?))),
        SolverKind::Lagrangian if two_fluid() == Some(true) => Ok(Ok(WarmStart::Profiles(profiles(from)?))),
        SolverKind::Lagrangian => {
            Ok(saltus_solvers::run::checkpoint::read(from).map_err(|e| e.to_string()).and_then(|r| {
                let w = WarmStart::State(Box::new(r));
                saltus_solvers::warm_start_refusal(scene, &w).map_or(Ok(w), Err)
            }))
        }
    }
}

/// Run `scene` into `out` as `settings` say, showing progress on `bar` (see
/// [`progress_bar`]; a hidden bar gets a line on stderr every
/// [`RunSettings::log_every`]), then draw `profiles.png` in `out` from the state the run
/// returned, whatever its ending. An interrupt (see [`catch_interrupt`]) stops the run
/// with its outputs written. Reference data that cannot be read gives a warning, not a
/// failure.
pub fn run_scene(scene: &Scene, out: &Path, bar: &ProgressBar, settings: &RunSettings) -> RunOutcome {
    run_scene_with(scene, out, bar, settings, &mut |_| interrupted())
        .unwrap_or_else(|e| RunOutcome::failed(e.to_string()))
}

/// [`run_scene`] for callers with their own way to stop a run: `stop` is asked after
/// every unit of work and ends the run (`interrupted`, outputs written) when it returns
/// true. `Err` is the solver's own error (the scene cannot be set up, the outputs cannot
/// be written), typed for callers that tell bad input from a failed write.
pub fn run_scene_with(
    scene: &Scene,
    out: &Path,
    bar: &ProgressBar,
    settings: &RunSettings,
    stop: &mut dyn FnMut(&Progress) -> bool,
) -> Result<RunOutcome, saltus_core::Error> {
    run_scene_observed(scene, out, bar, settings, stop, None)
}

/// An observer after another: the second sees a unit of work only when the first lets
/// the run go on.
struct Chain<'a, 'b> {
    first: &'a mut dyn Observer,
    second: Option<&'b mut dyn Observer>,
}

impl Observer for Chain<'_, '_> {
    fn start(&mut self, stepper: &dyn Stepper, clock: &Clock) {
        self.first.start(stepper, clock);
        if let Some(o) = self.second.as_deref_mut() {
            o.start(stepper, clock);
        }
    }
    fn step(&mut self, stepper: &dyn Stepper, progress: &Progress, clock: &Clock) -> Control {
        match self.first.step(stepper, progress, clock) {
            Control::Continue => {
                self.second.as_deref_mut().map_or(Control::Continue, |o| o.step(stepper, progress, clock))
            }
            other => other,
        }
    }
    fn finish(&mut self, stepper: &dyn Stepper, ending: &Ending, clock: &Clock) {
        self.first.finish(stepper, ending, clock);
        if let Some(o) = self.second.as_deref_mut() {
            o.finish(stepper, ending, clock);
        }
    }
}

/// [`run_scene_with`] with one more observer of every unit of work after the progress
/// display (the pooled stopping rule of several seeds, [`crate::seeds`]).
pub fn run_scene_observed(
    scene: &Scene,
    out: &Path,
    bar: &ProgressBar,
    settings: &RunSettings,
    stop: &mut dyn FnMut(&Progress) -> bool,
    extra: Option<&mut dyn Observer>,
) -> Result<RunOutcome, saltus_core::Error> {
    let mut last: Option<Instant> = None;
    let started = Instant::now();
    let mut next_line = settings.log_every.unwrap_or(Duration::MAX);
    let mut phase: Option<(Phase, Instant, f64)> = None;
    let label = if bar.prefix().is_empty() { scene.meta.name.clone() } else { bar.prefix() };
    let mut observer = |p: &Progress| {
        // a closure registered at run time that failed (its function raised) returns NaN
        // from then on: stop at once, before the solver reports a breakdown
        if stop(p) || scene.closures.failure().is_some() {
            return Control::Stop;
        }
        if phase.map(|(ph, ..)| ph) != Some(p.phase) {
            phase = Some((p.phase, Instant::now(), p.time));
            if !bar.is_hidden() {
                bar.set_style(template(&bar.prefix(), "[{elapsed_precise}] {bar:30.cyan/blue} eta {eta:>4} {msg}"));
                // the bar's pace, as the line's, counts from where the run entered the
                // phase (a checkpoint's time): the jump to it is not progress
                bar.set_length((p.end_time * TICKS_PER_SECOND) as u64);
                bar.set_position((p.time * TICKS_PER_SECOND) as u64);
                bar.reset_eta();
                last = None;
            }
        }
        let (phase_wall, t0) = phase.map_or((0.0, 0.0), |(_, t, t0)| (t.elapsed().as_secs_f64(), t0));
        if bar.is_hidden() {
            let Some(every) = settings.log_every.filter(|e| !e.is_zero()) else { return Control::Continue };
            let elapsed = started.elapsed();
            if elapsed >= next_line {
                while next_line <= elapsed {
                    next_line += every;
                }
                let left = eta(p, phase_wall, t0).map_or_else(String::new, |e| format!("  eta {e:.0} s"));
                crate::errln!("{label}: [{:.0} s] {}{left}", elapsed.as_secs_f64(), describe(p));
            }
        } else if !matches!(last, Some(t) if t.elapsed() < Duration::from_millis(50)) {
            last = Some(Instant::now());
            bar.set_length((p.end_time * TICKS_PER_SECOND) as u64);
            bar.set_position((p.time * TICKS_PER_SECOND) as u64);
            bar.set_message(describe(p));
        }
        Control::Continue
    };
    let options = saltus_solvers::RunOptions {
        restart: settings.restart.clone(),
        max_wall: settings.max_wall,
        warm_start: settings.warm_start.clone(),
    };
    let result = saltus_solvers::run_with(scene, out, &mut Chain { first: &mut observer, second: extra }, &options);
    bar.finish_and_clear();
    let run = result?;
    let mut warnings = Vec::new();
    let png = out.join(FIGURE);
    let figure = match draw_run(scene, &run.report, &run.ending, &png, &mut warnings) {
        Ok(()) => Some(png),
        Err(e) => {
            warnings.push(format!("{}: cannot draw: {e:#}", png.display()));
            None
        }
    };
    let phase_figures = crate::figures::phases::draw(out, &scene.label()).unwrap_or_else(|e| {
        warnings.push(format!("{}: cannot draw the phase averages: {e:#}", out.display()));
        Vec::new()
    });
    let error = match &run.ending {
        _ if scene.closures.failure().is_some() => scene.closures.failure(),
        Ending::Unstable(b) => Some(format!("unstable at {b}")),
        Ending::Interrupted => Some(format!("interrupted at t = {} s", decimal(run.report.summary.sim_time_s))),
        Ending::Steady | Ending::EndTime | Ending::TargetError | Ending::MaxSteps | Ending::WallClock => None,
    };
    Ok(RunOutcome {
        ending: Some(run.ending),
        report: Some(run.report),
        error,
        figure,
        phase_figures,
        warnings,
        wall: run.wall,
    })
}

fn draw_run(
    scene: &Scene,
    r: &RunReport,
    ending: &Ending,
    png: &Path,
    warnings: &mut Vec<String>,
) -> anyhow::Result<()> {
    let reference = match load_reference(scene) {
        Ok(r) => r,
        Err(e) => {
            warnings.push(format!("{e:#}; {} drawn without reference data", png.display()));
            Vec::new()
        }
    };
    let s = &r.summary;
    let name = scene.label();
    let t = decimal(s.sim_time_s);
    let title = match (ending, s.qs_star, s.shields) {
        (Ending::Unstable(_) | Ending::Interrupted, _, _) => {
            format!("{name}: stopped ({}) at t = {t} s, last good state", s.ending)
        }
        (_, Some(q), Some(sh)) => format!("{name}: {} at t = {t} s, qs* = {q:.3}, Shields {sh:.3}", s.ending),
        _ => format!("{name}: {} at t = {t} s, no transport measured", s.ending),
    };
    let reference: Vec<Reference> = reference.iter().map(|(label, table)| Reference { label, table }).collect();
    draw_profiles(&title, &RUN_PANELS, &[(name, &r.profiles)], &reference, png)
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
        None => PathBuf::from("out").join(s.label()),
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

    #[test]
    fn the_time_left_counts_the_pace_from_where_the_run_entered_its_phase() {
        let p = Progress {
            phase: Phase::Flow,
            time: 110.0,
            end_time: 150.0,
            steps: 0,
            total_steps: 0,
            dt: 1e-4,
            residual: None,
        };
        // from rest: 110 s of flow in 10 s of wall time
        assert!((eta(&p, 10.0, 0.0).unwrap() - 40.0 / 11.0).abs() < 1e-12);
        // restarted at 100 s: 10 s of flow in 10 s
        assert!((eta(&p, 10.0, 100.0).unwrap() - 40.0).abs() < 1e-12);
        assert_eq!(eta(&p, 10.0, 110.0), None);
    }
}
