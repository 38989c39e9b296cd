//! The DEM run that stops when its answer is known: `solver.lagrangian.target_error` ends
//! the run (`ending = "target_error"`) once the transport rate over the averaging window
//! that MSER-5 finds in the run's own qs(t) has that relative standard error, and the
//! answer agrees with a longer run averaged after its spin-up. Bad values are refused by
//! `check` and `run` alike.

mod common;

use common::*;
use std::path::Path;

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).expect("summary.json")).expect("json")
}

fn scene() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes/small_dem_bed.toml")
}

/// The small bed run with fluid periods of 2 ms and `set` into a fresh folder `name`: its
/// summary.
fn run(name: &str, set: &[&str]) -> serde_json::Value {
    let s = scene();
    let out = tmp_dir(name);
    let mut args = vec!["run", s.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    for x in ["solver.lagrangian.fluid_period=2e-3"].iter().chain(set) {
        args.extend(["--set", x]);
    }
    let o = saltus(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    summary(&out)
}

#[test]
fn a_dem_run_stops_at_its_target_error_with_an_answer_a_longer_run_confirms() {
    let a = run("target_error_short", &["solver.lagrangian.end_time=30", "solver.lagrangian.target_error=0.02"]);
    assert_eq!(a["ending"], "target_error", "{a}");
    let (t, start) = (a["sim_time_s"].as_f64().unwrap(), a["window_start_s"].as_f64().unwrap());
    assert!(t < 30.0 && start > 0.0 && start <= 0.5 * t + 1e-9, "stopped at {t} s, window from {start} s");
    let (q, e) = (a["qs_window"].as_f64().unwrap(), a["qs_window_stderr"].as_f64().unwrap());
    assert!(e > 0.0 && e <= 0.02 * q, "qs {q} +- {e}");
    // the same bed run on to 16 s: its own window (its error may be beyond its blocks: a
    // 57-grain bed fluctuates slowly), against the short answer's error bar
    let b = run("target_error_long", &["solver.lagrangian.end_time=16"]);
    assert_eq!(b["ending"], "end_time");
    let ql = b["qs_window"].as_f64().unwrap();
    assert!((q - ql).abs() < 3.0 * e, "short {q} +- {e}, long {ql}");
}

#[test]
fn a_target_error_out_of_range_or_without_fluid_is_refused_alike() {
    let s = scene();
    for (name, v) in [("te_zero", "0"), ("te_negative", "-0.1"), ("te_nan", "nan"), ("te_above_one", "1.5")] {
        let set = format!("solver.lagrangian.target_error={v}");
        let out = tmp_dir(name);
        let check = assert_clean_failure(&saltus(&["check", s.to_str().unwrap(), "--set", &set]));
        assert!(check.contains("solver.lagrangian.target_error"), "{check}");
        let run = assert_clean_failure(&saltus(&[
            "run",
            s.to_str().unwrap(),
            "--set",
            &set,
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]));
        assert_eq!(run, check, "check and run disagree");
    }
    let dry = assert_clean_failure(&saltus(&[
        "check",
        s.to_str().unwrap(),
        "--set",
        "solver.lagrangian.fluid=\"off\"",
        "--set",
        "solver.lagrangian.target_error=0.02",
    ]));
    assert!(dry.contains("solver.lagrangian.target_error") && dry.contains("without fluid"), "{dry}");
}
