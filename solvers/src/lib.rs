//! # saltus-solvers
//!
//! Solvers of saltus: `eulerian` ([`eulerian`], the two-fluid column of Chassagne et al.
//! 2023) and `lagrangian` ([`lagrangian`], soft-sphere DEM coupled to the column, Maurin
//! et al. 2015). [`mod@column`] is the fluid column shared by both. [`resolve`] turns a
//! scene into its solver, the only place that dispatches on the solver type; [`run()`]
//! drives it ([`run::drive`]) and writes its outputs ([`output`]). [`measures`] are the
//! measures of profiles that the summaries of both solvers and the command line share.

// Errors carry file, key and message for the user; they are built once per failed run,
// never in a hot loop, so their size does not matter.
#![allow(clippy::result_large_err)]

pub mod column;
pub mod eulerian;
pub mod inputs;
pub mod lagrangian;
pub mod measures;
pub mod output;
pub mod run;
pub mod validate;

use std::fmt;
use std::path::{Path, PathBuf};

use saltus_core::scene::{Scene, SolverKind};
use saltus_core::Error;

pub use output::{Profiles, Summary};
pub use run::{Ending, Observer, Progress, Stepper, WarmStart};
pub use validate::validate;

/// Result of a run: what was written, and a paragraph for the terminal.
#[derive(Clone, Debug, Default)]
pub struct RunReport {
    /// profiles at the end of the run
    pub profiles: Profiles,
    /// the summary written to `summary.json`
    pub summary: Summary,
    /// one paragraph
    pub text: String,
}

impl fmt::Display for RunReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// How a run ended, with the last state: returned on every ending, after the outputs
/// are written.
#[derive(Clone, Debug)]
pub struct RunOutcome {
    /// why the run stopped
    pub ending: Ending,
    /// profiles, summary and paragraph of the last state (as written)
    pub report: RunReport,
    /// wall-clock time of the run (s)
    pub wall: f64,
}

/// The solver of `scene`, set up and ready to step. The only dispatch on the solver type.
pub fn resolve(scene: &Scene) -> Result<Box<dyn Stepper + '_>, Error> {
    Ok(match scene.solver.kind {
        SolverKind::Eulerian => {
            let cfg = eulerian::Config::from_scene(scene)?;
            let mut column = Box::new(eulerian::Eulerian::new(scene, cfg)?);
            if let Some(csv) = &scene.domain.initial_profiles {
                let key = |message: String| Error::Key {
                    file: scene.path.clone(),
                    key: saltus_core::scene::initial::KEY.into(),
                    message,
                };
                let mut p = Profiles::default();
                for (name, values) in &scene.domain.initial_columns {
                    p.push(name, values.clone());
                }
                column.warm_start(&WarmStart::Profiles(p)).map_err(|m| key(format!("{csv}: {m}")))?;
            }
            column
        }
        SolverKind::Lagrangian => {
            let cfg = lagrangian::Config::from_scene(scene)?;
            Box::new(lagrangian::Lagrangian::new(scene, cfg)?)
        }
    })
}

/// How a run starts and what, besides the scene, may stop it.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// continue from the checkpoint in this folder (or this file) instead of the scene's
    /// initial state ([`run::checkpoint`])
    pub restart: Option<PathBuf>,
    /// stop after this many wall-clock seconds ([`Ending::WallClock`]; the outputs and a
    /// checkpoint are written as at any other end)
    pub max_wall: Option<f64>,
    /// start from another run's final state ([`Stepper::warm_start`]; see
    /// [`warm_start_refusal`]) instead of the scene's initial state; not with `restart`
    pub warm_start: Option<WarmStart>,
}

/// Why `scene` cannot start warm from `from`, if it cannot, told before anything is set
/// up (so that a caller may start it from rest instead): a DEM scene takes the grains of a
/// DEM checkpoint whose scene makes the same grains
/// ([`lagrangian::run::warm::refusal`]) or the velocities of profiles; an Eulerian scene
/// takes profiles. Profiles are checked by the solver as it takes them.
pub fn warm_start_refusal(scene: &Scene, from: &WarmStart) -> Option<String> {
    match (scene.solver.kind, from) {
        (SolverKind::Eulerian, WarmStart::State(r)) => Some(eulerian::checkpoint_refusal(r)),
        (SolverKind::Eulerian, WarmStart::Profiles(_)) => None,
        (SolverKind::Lagrangian, WarmStart::State(r)) => lagrangian::run::warm::refusal(scene, r),
        (SolverKind::Lagrangian, WarmStart::Profiles(_)) => None,
    }
}

/// Run `scene`, writing its outputs into `out`. `observer` sees every unit of work and
/// may stop the run ([`Ending::Interrupted`]). Every ending, an unstable one included,
/// writes the last state and returns it; `Err` only when the scene cannot be set up or
/// the outputs cannot be written.
pub fn run(scene: &Scene, out: &Path, observer: &mut dyn Observer) -> Result<RunOutcome, Error> {
    run_with(scene, out, observer, &RunOptions::default())
}

/// [`run()`], from a checkpoint when `options` says so. An output folder where the run
/// would write over one of its inputs is refused ([`output::check_out`]). The output
/// folder is made first,
/// before the set-up and any deposition, with `timeseries.csv` in it; the time series,
/// snapshots and checkpoints are written while the run goes ([`run::history`]). A
/// checkpoint that is missing, damaged, of another solver or of a scene that differs in
/// a key that matters is refused before anything is made, naming the file and the keys;
/// so is a warm start the scene cannot take ([`warm_start_refusal`]).
pub fn run_with(
    scene: &Scene,
    out: &Path,
    observer: &mut dyn Observer,
    options: &RunOptions,
) -> Result<RunOutcome, Error> {
    output::check_out(out, scene)?;
    let restart = options.restart.as_deref().map(run::checkpoint::read).transpose()?;
    if let Some(r) = &restart {
        check_restart(scene, r)?;
    }
    let warm_refused = |m: String| Error::Invalid(format!("{}: warm start: {m}", scene.path.display()));
    if let Some(w) = &options.warm_start {
        if restart.is_some() {
            return Err(Error::Invalid(format!(
                "{}: a run restarts from a checkpoint or starts warm, not both",
                scene.path.display()
            )));
        }
        if let Some(m) = warm_start_refusal(scene, w) {
            return Err(warm_refused(m));
        }
    }
    let created = !out.exists();
    // a folder that cannot be made fails before the work, not after it
    std::fs::create_dir_all(out).map_err(|source| Error::Io { file: out.to_path_buf(), source })?;
    let mut stepper = match resolve(scene) {
        Ok(s) => s,
        Err(e) => {
            if created {
                // refused at set-up: leave no empty folder behind (fails harmlessly if not empty)
                let _ = std::fs::remove_dir(out);
            }
            return Err(e);
        }
    };
    if let Some(r) = &restart {
        let fail = |m: String| Error::Invalid(format!("{}: {m}", r.file.display()));
        if !stepper.restartable() || stepper.name() != r.solver {
            return Err(fail(format!(
                "written by the {} solver; the scene runs the {} solver, which {}",
                r.solver,
                stepper.name(),
                if stepper.restartable() { "cannot take its state" } else { "has no restart" }
            )));
        }
        stepper.restore(&r.state).map_err(fail)?;
    }
    if let Some(w) = &options.warm_start {
        stepper.warm_start(w).map_err(warm_refused)?;
    }
    let mut recorder = run::Recorder::start(out, scene, stepper.as_ref(), restart.as_ref())?;
    let resumed = recorder.resumed_clock();
    let cpu_before = run::cpu::thread_seconds().zip(stepper.worker_cpu());
    let mut phases = run::PhaseAverages::of_scene(scene);
    let driven = match phases.as_mut() {
        Some(p) => run::drive_with(stepper.as_mut(), &mut [&mut recorder, p, observer], options.max_wall, resumed),
        None => run::drive_with(stepper.as_mut(), &mut [&mut recorder, observer], options.max_wall, resumed),
    };
    if let Some(p) = &phases {
        p.write(out, scene.physics.forcing.as_ref())?;
    }
    let mut report = stepper.report(&driven.ending, &driven.clock);
    if let Some(p) = &phases {
        let net = p.net();
        report.summary.net_transport = net.per_period;
        report.summary.net_transport_stderr = net.error;
        if let Some(q) = net.per_period {
            let error = net.error.map_or_else(String::new, |e| format!(" +- {e:.3e}"));
            report.text.push_str(&format!(
                "; net transport {q:.4e}{error} m^2 per period over {} periods after {} of spin-up",
                net.periods, net.spin_up_periods
            ));
        }
    }
    report.summary.cpu_time_s = run::cpu::thread_seconds()
        .zip(stepper.worker_cpu())
        .zip(cpu_before)
        .map(|((own, workers), (own0, workers0))| (own - own0) + (workers - workers0));
    let timing = driven.timing(stepper.as_ref());
    report.text.push_str("; ");
    report.text.push_str(&timing.line());
    report.summary.timing = Some(timing);
    if let Some(e) = recorder.paraview_error() {
        report.text.push_str("; ");
        report.text.push_str(e);
    }
    output::write_run(out, scene, &report.profiles, &report.summary)?;
    recorder.finish()?;
    Ok(RunOutcome { ending: driven.ending, report, wall: driven.clock.wall })
}

/// Refuse a checkpoint written for another solver or a scene that differs from `scene`
/// in a key that changes the run, naming the file and every such key.
fn check_restart(scene: &Scene, r: &run::checkpoint::Restart) -> Result<(), Error> {
    let solver = scene.solver.kind.name();
    let file = r.file.display();
    if r.solver != solver {
        return Err(Error::Invalid(format!(
            "{file}: written by a {} run; {} runs the {solver} solver (solver.type)",
            r.solver,
            scene.path.display()
        )));
    }
    let now = scene.to_toml()?;
    let saved = r.resolved_scene(&scene.path);
    let keys =
        run::checkpoint::scene_differences(&saved, &now, solver).map_err(|e| Error::Invalid(format!("{file}: {e}")))?;
    if keys.is_empty() {
        return Ok(());
    }
    Err(Error::Invalid(format!(
        "{file}: the scene differs from the checkpoint's in {}; {}: restart with the scene of the checkpoint (only output, meta, reference, end_time, max_steps, threads, vtk_period and stop_when_steady may change)",
        keys.join(", "),
        scene.path.display()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A checkpoint written before a key existed (absent from its scene) restarts when the
    /// key is at its default, the behaviour it ran with; a changed value is still refused.
    #[test]
    fn a_key_added_since_the_checkpoint_takes_its_default() {
        saltus_closures::link();
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/verification/dem_binary_collision.toml");
        let scene = Scene::from_file(&path).unwrap();
        let mut saved: toml::Table = scene.to_toml().unwrap().parse().unwrap();
        let contact = saved["particles"]["contact"].as_table().unwrap().clone();
        assert!(contact.contains_key("normal_force"));
        let mut old = contact.clone();
        old.remove("normal_force");
        saved["particles"].as_table_mut().unwrap().insert("contact".into(), toml::Value::Table(old));
        let restart = run::checkpoint::Restart {
            dir: path.clone(),
            file: path.clone(),
            solver: "lagrangian".into(),
            scene: saved.to_string(),
            cadence: Default::default(),
            state: Vec::new(),
        };
        check_restart(&scene, &restart).unwrap();
        let repulsive = Scene::from_file_with(&path, &["particles.contact.normal_force=\"repulsive\"".into()]).unwrap();
        let e = check_restart(&repulsive, &restart).unwrap_err().to_string();
        assert!(e.contains("particles.contact.normal_force"), "{e}");
    }
}
