//! The run driver: `saltus_solvers::run` returns the last state on every ending, after
//! writing it, for both solvers.

mod common;

use std::path::{Path, PathBuf};

use saltus_core::scene::{Scene, SolverKind};
use saltus_solvers::run::{Control, Ending, Phase, Quiet};
use saltus_solvers::Progress;

fn scene(name: &str, set: &[&str]) -> Scene {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("cases").join(name);
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Scene::from_file_with(file, &set).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn tmp_out(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("saltus_run_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn written_summary(out: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json written");
    serde_json::from_str(&text).expect("json")
}

#[test]
fn the_solver_type_is_resolved_once_and_unknown_ones_are_refused() {
    assert_eq!(scene("chassagne2023/case01.toml", &[]).solver.kind, SolverKind::Eulerian);
    assert_eq!(scene("verification/dem_settling.toml", &[]).solver.kind, SolverKind::Lagrangian);
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let e = Scene::from_file_with(file, &["solver.type=\"sph\"".to_string()]).expect_err("refused").to_string();
    assert!(e.contains("case01.toml") && e.contains("solver.type") && e.contains("`eulerian` or `lagrangian`"), "{e}");
}

#[test]
fn an_eulerian_run_to_its_end_time_returns_the_state_it_wrote() {
    let s = scene("chassagne2023/case01.toml", &["domain.cells=60", "solver.eulerian.end_time=0.5"]);
    let out = tmp_out("eulerian_end_time");
    let r = saltus_solvers::run(&s, &out, &mut Quiet).expect("runs");
    assert_eq!(r.ending, Ending::EndTime);
    let sum = &r.report.summary;
    assert!((sum.sim_time_s - 0.5).abs() < 1e-9, "{}", sum.sim_time_s);
    assert_eq!((sum.ending.as_str(), sum.error.as_deref(), sum.steady), ("end_time", None, false));
    assert_eq!(r.report.profiles.get("z").map(<[f64]>::len), Some(60));
    let w = written_summary(&out);
    assert_eq!(w["ending"].as_str(), Some("end_time"));
    assert_eq!(w["steps"].as_u64(), Some(sum.steps as u64));
    let (written, returned) = (w["qs"].as_f64().expect("qs written"), sum.qs.expect("qs measured"));
    // JSON's shortest decimal reads back to within one unit in the last place
    assert!((written / returned - 1.0).abs() < 1e-15, "{written} vs {returned}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn an_interrupted_dem_run_writes_and_returns_its_state() {
    let s = scene("verification/dem_settling.toml", &[]);
    let out = tmp_out("dem_interrupted");
    let mut seen = 0u64;
    let mut stop_after_three = |p: &Progress| {
        assert_eq!(p.phase, Phase::Flow, "a list start has no deposition");
        seen += 1;
        if seen >= 3 {
            Control::Stop
        } else {
            Control::Continue
        }
    };
    let r = saltus_solvers::run(&s, &out, &mut stop_after_three).expect("an interruption is an outcome");
    assert_eq!(r.ending, Ending::Interrupted);
    let sum = &r.report.summary;
    // the first unit ends at the first fluid update (after one DEM step), the next two
    // one fluid period of 0.01 s later each
    assert!(sum.sim_time_s > 0.02 && sum.sim_time_s < 0.021, "{}", sum.sim_time_s);
    assert_eq!(sum.ending, "interrupted");
    assert!(sum.error.is_some() && sum.mass_error.is_none() && sum.rejected_steps.is_none());
    let w = written_summary(&out);
    assert_eq!(w["ending"].as_str(), Some("interrupted"));
    // a single sphere in still water: qs is measured from the samples taken (zero: it
    // falls straight down), written as returned
    assert_eq!(w["qs"].as_f64(), sum.qs);
    assert!(sum.qs.is_some());
    let _ = std::fs::remove_dir_all(&out);
}

/// The stages of `summary.json`'s `timing`, which must add up to its wall time.
fn stages(out: &Path) -> (f64, serde_json::Map<String, serde_json::Value>) {
    let w = written_summary(out);
    let t = &w["timing"];
    let wall = t["wall"].as_f64().expect("timing.wall");
    let stages = t["stages"].as_object().expect("timing.stages").clone();
    let sum: f64 = stages.values().map(|v| v.as_f64().expect("seconds")).sum();
    assert!(stages.values().all(|v| v.as_f64().is_some_and(|s| s >= 0.0)), "{stages:?}");
    assert!((sum - wall).abs() <= 1e-9 * wall.max(1.0), "stages {sum} s against the wall {wall} s");
    (wall, stages)
}

#[test]
fn every_run_writes_its_wall_time_by_stage() {
    let s = scene("chassagne2023/case01.toml", &["domain.cells=60", "solver.eulerian.end_time=0.5"]);
    let out = tmp_out("eulerian_timing");
    let r = saltus_solvers::run(&s, &out, &mut Quiet).expect("runs");
    let (_, st) = stages(&out);
    for k in ["coefficients", "momentum", "granular", "turbulence", "volume_fraction", "output", "other"] {
        assert!(st.contains_key(k), "{k} missing from {st:?}");
    }
    // every step solves the momentum and evaluates the coefficients
    assert!(st["momentum"].as_f64() > Some(0.0) && st["coefficients"].as_f64() > Some(0.0), "{st:?}");
    assert!(r.report.text.contains("wall time") && r.report.text.contains("coefficients"), "{}", r.report.text);
    let _ = std::fs::remove_dir_all(&out);

    // a coupled DEM run: the engine's stages, the coupling's and the driver's
    let set: Vec<&str> = common::TINY_COUPLED_BED
        .iter()
        .copied()
        .chain(["solver.lagrangian.end_time=0.03", "solver.lagrangian.stats_start=0.0"])
        .collect();
    let s = scene("chassagne2023/case01.toml", &set);
    let out = tmp_out("dem_timing");
    saltus_solvers::run(&s, &out, &mut Quiet).expect("runs");
    let (_, st) = stages(&out);
    for k in ["neighbours", "pair_forces", "integration", "drag", "fluid_column", "averaging", "sampling"] {
        assert!(st[k].as_f64() > Some(0.0), "{k}: {st:?}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_wall_clock_limit_ends_a_run_with_its_outputs_and_a_checkpoint() {
    let s = scene("verification/dem_settling.toml", &[]);
    let out = tmp_out("dem_wall_clock");
    let options = saltus_solvers::RunOptions { max_wall: Some(0.0), ..Default::default() };
    let r = saltus_solvers::run_with(&s, &out, &mut Quiet, &options).expect("an outcome");
    assert_eq!(r.ending, Ending::WallClock);
    assert_eq!(written_summary(&out)["ending"].as_str(), Some("wall_clock"));
    assert!(out.join("checkpoint.bin").is_file(), "a checkpoint to go on from");
    // and it goes on from there to the scene's end
    let options = saltus_solvers::RunOptions { restart: Some(out.clone()), ..Default::default() };
    let r = saltus_solvers::run_with(&s, &out, &mut Quiet, &options).expect("restarts");
    assert_eq!(r.ending, Ending::EndTime);
    let _ = std::fs::remove_dir_all(&out);
}
