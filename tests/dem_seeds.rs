//! `saltus run SCENE --seeds N`: N seeds of a DEM scene as one answer. With
//! `solver.lagrangian.target_error` the seeds stop together when the pooled transport rate
//! (the mean of the seeds' window means) has that relative standard error; each seed's
//! outputs are those of the same seed run alone to the same time. Bad input is refused by
//! name.

mod common;

use common::*;
use std::path::Path;

fn json(file: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(file).expect("json file")).expect("json")
}

fn scene() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes/small_dem_bed.toml")
}

const COMMON: [&str; 3] = ["solver.lagrangian.fluid_period=2e-3", "solver.lagrangian.end_time=30", "seed=3"];

fn run(out: &Path, extra: &[&str], set: &[&str]) -> std::process::Output {
    let s = scene();
    let mut args = vec!["run", s.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    args.extend(extra);
    for x in COMMON.iter().chain(set) {
        args.extend(["--set", x]);
    }
    saltus(&args)
}

#[test]
fn two_seeds_stop_together_at_the_pooled_error_and_each_is_its_run_alone() {
    let out = tmp_dir("seeds_pooled");
    let o = run(&out, &["--seeds", "2"], &["solver.lagrangian.target_error=0.05"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc = json(&out.join("seeds.json"));
    assert_eq!(doc["ending"], "target_error", "{doc}");
    let runs = doc["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 2);
    let t: Vec<f64> = runs.iter().map(|r| r["sim_time_s"].as_f64().unwrap()).collect();
    assert_eq!(t[0], t[1], "the seeds stop at one time");
    assert!(t[0] < 30.0, "stopped at {t:?}");
    // the pooled answer: the mean of the window means, its error the larger of the within-
    // and between-seed errors, at or below the target
    let q: Vec<f64> = runs.iter().map(|r| r["qs_window"].as_f64().unwrap()).collect();
    let e: Vec<f64> = runs.iter().map(|r| r["qs_window_stderr"].as_f64().unwrap()).collect();
    let mean = 0.5 * (q[0] + q[1]);
    let within = (e[0] * e[0] + e[1] * e[1]).sqrt() / 2.0;
    let between = (q[0] - q[1]).abs() / 2.0;
    let pooled = doc["qs"].as_f64().unwrap();
    let err = doc["qs_stderr"].as_f64().unwrap();
    assert!((pooled - mean).abs() <= 1e-12 * mean, "{pooled} vs {mean}");
    assert!((err - within.max(between)).abs() <= 1e-12 * err, "{err} vs {within} / {between}");
    assert!(err <= 0.05 * pooled, "{err} over {pooled}");
    let (qs_star, qs_star_err) = (doc["qs_star"].as_f64().unwrap(), doc["qs_star_stderr"].as_f64().unwrap());
    assert!((qs_star_err / qs_star - err / pooled).abs() <= 1e-12, "qs* error {qs_star_err} of {qs_star}");
    for r in runs {
        let s = json(&Path::new(r["dir"].as_str().unwrap()).join("summary.json"));
        assert_eq!(s["ending"], "target_error");
    }
    // the second seed alone to the time the pool stopped at: the same window, bit for bit
    let alone = tmp_dir("seeds_alone");
    let end = format!("solver.lagrangian.end_time={}", t[1]);
    let o = run(&alone, &[], &["seed=4", &end]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = json(&alone.join("summary.json"));
    assert_eq!(s["qs_window"].as_f64(), Some(q[1]), "seed 4 alone: {s}");
}

#[test]
fn seeds_out_of_range_an_eulerian_scene_or_a_restart_are_refused() {
    let out = tmp_dir("seeds_refused");
    for n in ["0", "257"] {
        let msg = assert_clean_failure(&run(&out, &["--seeds", n], &[]));
        assert!(msg.contains(&format!("--seeds {n}")) && msg.contains("[1, 256]"), "{msg}");
    }
    let eulerian = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/chassagne2023/case01.toml");
    let msg = assert_clean_failure(&saltus(&[
        "run",
        eulerian.to_str().unwrap(),
        "--seeds",
        "2",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]));
    assert!(msg.contains("--seeds") && msg.contains("lagrangian"), "{msg}");
    let msg = assert_clean_failure(&run(&out, &["--seeds", "2", "--restart", out.to_str().unwrap()], &[]));
    assert!(msg.contains("--seeds") && msg.contains("--restart"), "{msg}");
    let bad = assert_clean_failure(&saltus(&["run", scene().to_str().unwrap(), "--seeds", "two"]));
    assert!(bad.contains("--seeds"), "{bad}");
}

/// `--seeds N --warm-start BANK` where BANK is the output of a run of N seeds or more: each
/// seed starts from its own parent's bed (the first row's Shields number, read off the
/// carried column, is that parent's last), so that the pooled answer's scatter is one
/// between beds; fewer parents than seeds, a single run from such a folder, and seeds of a
/// scene without random draws from one developed state are refused.
#[test]
fn seeds_from_a_bank_of_developed_states_start_each_from_its_own() {
    let bank = tmp_dir("seeds_bank");
    let short = ["solver.lagrangian.end_time=0.05"];
    let o = run(&bank, &["--seeds", "2"], &short);
    assert!(o.status.success(), "{}", stderr(&o));
    let answer = tmp_dir("seeds_from_bank");
    let o = run(&answer, &["--seeds", "2", "--warm-start", bank.to_str().unwrap()], &short);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = |dir: &Path| {
        let (h, rows) = read_table(&dir.join("timeseries.csv"));
        let v = |r: &[String]| cell(&h, r, "shields").parse::<f64>().unwrap();
        (v(&rows[0]), v(rows.last().unwrap()))
    };
    let (p3, p4) = (rows(&bank.join("seed_3")).1, rows(&bank.join("seed_4")).1);
    let (c3, c4) = (rows(&answer.join("seed_3")).0, rows(&answer.join("seed_4")).0);
    assert!(p3 > 0.0 && p4 > 0.0 && p3 != p4, "two beds: {p3} {p4}");
    assert!((c3 - p3).abs() <= 1e-12 * p3 && (c4 - p4).abs() <= 1e-12 * p4, "{c3} {c4} from {p3} {p4}");

    let o = run(&tmp_dir("seeds_bank_short"), &["--seeds", "3", "--warm-start", bank.to_str().unwrap()], &short);
    let e = stderr(&o);
    assert!(!o.status.success() && e.contains("3 developed states") && e.contains("holds 2"), "{e}");
    let o = run(&tmp_dir("seeds_bank_single"), &["--warm-start", bank.to_str().unwrap()], &short);
    let e = stderr(&o);
    assert!(!o.status.success() && e.contains("--seeds N") && e.contains("seed_<k>"), "{e}");
    // without a fluctuation closure nothing random is left after the deposition: seeds from
    // one developed state would be one run twice
    let one = bank.join("seed_3");
    let o = run(&tmp_dir("seeds_one_state"), &["--seeds", "2", "--warm-start", one.to_str().unwrap()], &short);
    let e = stderr(&o);
    assert!(!o.status.success() && e.contains("no random numbers") && e.contains("closures.fluctuation"), "{e}");
}
