//! Checkpoints and restarts: a DEM run stopped at a checkpoint and restarted ends bit for
//! bit where the uninterrupted run does, from the flow and from the deposition; a
//! restart from a scene that differs, or from a damaged checkpoint, is refused.

mod common;

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_solvers::run::{Control, Phase, Quiet};
use saltus_solvers::{Profiles, Progress, RunOptions, WarmStart};

/// A bed of a few hundred grains in a box of 6 x 6 diameters: a deposition of 0.05 s,
/// then 0.12 s of flow with the statistics from the start, a drag fluctuation closure
/// (random streams per particle) and k-omega (turbulence state in the column).
fn scene(extra: &[&str]) -> Scene {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let mut set: Vec<String> = common::TINY_COUPLED_BED
        .iter()
        .copied()
        .chain([
            "solver.lagrangian.end_time=0.12",
            "solver.lagrangian.stats_start=0.0",
            "closures.turbulence={type=\"k_omega\"}",
            "closures.fluctuation={type=\"drw\"}",
            "output.timeseries_interval=0.005",
            "output.snapshot_interval=0.04",
        ])
        .map(|s| s.to_string())
        .collect();
    set.extend(extra.iter().map(|s| s.to_string()));
    Scene::from_file_with(&file, &set).unwrap_or_else(|e| panic!("{e}"))
}

fn tmp_out(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("saltus_restart_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{}: {e}", dir.join(file).display()))
}

/// summary.json without what depends on the wall clock.
fn summary(dir: &Path) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_str(&read(dir, "summary.json")).expect("json");
    let m = v.as_object_mut().expect("object");
    // the wall times are the process's, never the same twice
    m.remove("wall_time_s");
    m.remove("particle_steps_per_s");
    m.remove("timing");
    v
}

/// Run uninterrupted; run again stopped at the first unit of `phase` at or after `at`
/// (simulated s of that phase), then restarted from the checkpoint that the stop wrote,
/// into the same folder. Both must write the same bytes.
fn stop_and_restart(name: &str, phase: Phase, at: f64, extra: &[&str]) {
    stop_and_restart_from(name, phase, at, extra, None)
}

/// [`stop_and_restart`] for runs that start from `warm` (the restart takes only the
/// checkpoint).
fn stop_and_restart_from(name: &str, phase: Phase, at: f64, extra: &[&str], warm: Option<WarmStart>) {
    let s = scene(extra);
    let whole = tmp_out(&format!("{name}_whole"));
    let start = RunOptions { warm_start: warm, ..Default::default() };
    let r = saltus_solvers::run_with(&s, &whole, &mut Quiet, &start).expect("runs");
    assert_eq!(r.ending.name(), "end_time");

    let parts = tmp_out(&format!("{name}_parts"));
    let mut stop = |p: &Progress| if p.phase == phase && p.time >= at { Control::Stop } else { Control::Continue };
    let first = saltus_solvers::run_with(&s, &parts, &mut stop, &start).expect("an interruption is an outcome");
    assert_eq!(first.ending.name(), "interrupted");
    assert!(parts.join("checkpoint.bin").is_file());
    let opts = RunOptions { restart: Some(parts.clone()), ..Default::default() };
    let second = saltus_solvers::run_with(&s, &parts, &mut Quiet, &opts).expect("restarts");
    assert_eq!(second.ending.name(), "end_time");

    // the granular fields (on by default with a fluid) are among the profiles compared
    assert!(read(&whole, "profiles.csv").lines().next().is_some_and(|h| h.contains(",p_p_contact,")));
    assert_eq!(read(&whole, "profiles.csv"), read(&parts, "profiles.csv"), "profiles.csv");
    assert_eq!(summary(&whole), summary(&parts), "summary.json");
    assert_eq!(read(&whole, "timeseries.csv"), read(&parts, "timeseries.csv"), "timeseries.csv");
    assert_eq!(read(&whole, "snapshots/index.csv"), read(&parts, "snapshots/index.csv"));
    for k in 0..2 {
        let f = format!("snapshots/profiles_{k:05}.csv");
        assert_eq!(read(&whole, &f), read(&parts, &f), "{f}");
    }
    // the restarted run wrote a checkpoint at its end too (not byte for byte the other's:
    // it holds the wall time of the flow, for the throughput), from which it can go on
    assert!(saltus_solvers::run::checkpoint::read(&parts).is_ok());
    let _ = std::fs::remove_dir_all(&whole);
    let _ = std::fs::remove_dir_all(&parts);
}

#[test]
fn a_run_restarted_in_the_flow_ends_bit_for_bit_as_the_uninterrupted_one() {
    stop_and_restart("flow", Phase::Flow, 0.055, &[]);
}

#[test]
fn a_run_restarted_in_the_deposition_ends_bit_for_bit_as_the_uninterrupted_one() {
    stop_and_restart("deposition", Phase::Setup, 0.02, &[]);
}

/// A run that starts its flow from a two-fluid run's velocities keeps them across a
/// checkpoint of its deposition: the restarted run starts its flow as the uninterrupted
/// one does (bit for bit), not from rest.
#[test]
fn a_run_started_from_profiles_and_restarted_in_its_deposition_ends_bit_for_bit() {
    let z: Vec<f64> = (0..40).map(|k| (k as f64 + 0.5) * 1e-3).collect();
    let phi = z.iter().map(|&z| if z < 0.012 { 0.6 } else { 0.0 }).collect();
    let u_f: Vec<f64> = z.iter().map(|&z| 20.0 * (z - 0.01).max(0.0)).collect();
    let u_p = u_f.iter().map(|u| 0.5 * u).collect();
    let mut p = Profiles::default();
    for (name, v) in [("z", z), ("phi", phi), ("u_f", u_f), ("u_p", u_p)] {
        p.push(name, v);
    }
    stop_and_restart_from("deposition_profiles", Phase::Setup, 0.02, &[], Some(WarmStart::Profiles(p)));
}

/// The DRW that spares the grains inside the bed reads a bed elevation the solver derives
/// from the solid fraction once per fluid update; a restored run must derive it again
/// before its first draw. A fixed redraw period off the fluid period's multiples puts
/// draws between the updates (the turnover time of this shallow bed is infinite, so the
/// draws would otherwise all fall on update steps, after the bed elevation is derived).
#[test]
fn a_run_whose_drw_spares_the_bed_restarts_bit_for_bit() {
    stop_and_restart(
        "above_bed",
        Phase::Flow,
        0.055,
        &["closures.fluctuation={type=\"drw\", above_bed=0.5, period=0.0037}"],
    );
}

#[test]
fn a_periodic_checkpoint_restarts_a_killed_run() {
    // checkpoints every 0.03 s of each phase; the run "dies" after 0.07 s of flow (the
    // observer stops it, then the stop's own checkpoint is replaced by the periodic one of
    // 0.06 s, as a SIGKILL would leave it): the rows written after 0.06 s are dropped
    let s = scene(&["output.checkpoint_interval=0.03"]);
    let whole = tmp_out("periodic_whole");
    saltus_solvers::run(&s, &whole, &mut Quiet).expect("runs");
    let parts = tmp_out("periodic_parts");
    let mut kept = None;
    let mut stop = |p: &Progress| {
        if p.phase == Phase::Flow && p.time >= 0.06 && kept.is_none() {
            kept = Some(std::fs::read(parts.join("checkpoint.bin")).expect("a periodic checkpoint"));
        }
        if p.phase == Phase::Flow && p.time >= 0.07 {
            Control::Stop
        } else {
            Control::Continue
        }
    };
    saltus_solvers::run(&s, &parts, &mut stop).expect("stops");
    std::fs::write(parts.join("checkpoint.bin"), kept.expect("checkpoint kept")).expect("write");
    let opts = RunOptions { restart: Some(parts.clone()), ..Default::default() };
    saltus_solvers::run_with(&s, &parts, &mut Quiet, &opts).expect("restarts");
    assert_eq!(read(&whole, "profiles.csv"), read(&parts, "profiles.csv"));
    assert_eq!(summary(&whole), summary(&parts));
    assert_eq!(read(&whole, "timeseries.csv"), read(&parts, "timeseries.csv"));
    let _ = std::fs::remove_dir_all(&whole);
    let _ = std::fs::remove_dir_all(&parts);
}

#[test]
fn a_restart_from_another_scene_or_a_bad_checkpoint_is_refused_by_name() {
    let s = scene(&["solver.lagrangian.end_time=0.02"]);
    let out = tmp_out("refused");
    saltus_solvers::run(&s, &out, &mut Quiet).expect("runs");
    let opts = RunOptions { restart: Some(out.clone()), ..Default::default() };
    // the end time, the output and the thread count may change
    let longer =
        scene(&["solver.lagrangian.end_time=0.03", "solver.lagrangian.threads=1", "output.snapshot_interval=0"]);
    let r = saltus_solvers::run_with(&longer, &out, &mut Quiet, &opts).expect("goes on");
    assert!((r.report.summary.sim_time_s - 0.03).abs() < 1e-4, "{}", r.report.summary.sim_time_s);
    let other = scene(&["solver.lagrangian.settle_time=0.06", "seed=5"]);
    let e = saltus_solvers::run_with(&other, &tmp_out("refused_other"), &mut Quiet, &opts)
        .expect_err("refused")
        .to_string();
    assert!(e.contains("checkpoint.bin") && e.contains("solver.lagrangian.settle_time") && e.contains("seed"), "{e}");
    let eulerian = scene(&["solver.type=\"eulerian\""]);
    let e = saltus_solvers::run_with(&eulerian, &tmp_out("refused_eulerian"), &mut Quiet, &opts)
        .expect_err("refused")
        .to_string();
    assert!(e.contains("checkpoint.bin") && e.contains("lagrangian") && e.contains("solver.type"), "{e}");
    let bytes = std::fs::read(out.join("checkpoint.bin")).expect("checkpoint");
    std::fs::write(out.join("checkpoint.bin"), &bytes[..bytes.len() - 100]).expect("write");
    let e = saltus_solvers::run_with(&s, &out, &mut Quiet, &opts).expect_err("refused").to_string();
    assert!(e.contains("checkpoint.bin") && e.contains("truncated"), "{e}");
    let missing = RunOptions { restart: Some(out.join("nowhere")), ..Default::default() };
    let e = saltus_solvers::run_with(&s, &out, &mut Quiet, &missing).expect_err("refused").to_string();
    assert!(e.contains("nowhere"), "{e}");
    let _ = std::fs::remove_dir_all(&out);
}

/// Cheng's eq 14 sums the slices of every DEM step of a fluid period, and eq 7's drag
/// reads the draws: a checkpoint written inside a period (a fluid period of several
/// thousand steps, the driver's unit being at most `CHECK_STEPS` of them) carries the
/// window, so the restarted run ends bit for bit as the uninterrupted one.
#[test]
fn a_run_with_the_period_mean_and_diffusion_of_phi_restarts_bit_for_bit() {
    stop_and_restart(
        "phi_window",
        Phase::Flow,
        0.055,
        &[
            "solver.lagrangian.fluid_period=0.1",
            "solver.lagrangian.phi_average=\"fluid_period\"",
            "solver.lagrangian.phi_diffusion=1",
            "closures.fluctuation={type=\"eim\", drag_reynolds=\"mean\"}",
        ],
    );
}
