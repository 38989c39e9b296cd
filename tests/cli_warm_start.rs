//! `saltus run --warm-start DIR`: a run started from the final state of another: a DEM run
//! from the grains (and, for the same case, the fluid column) of a DEM run, a DEM run from
//! the velocities of a two-fluid run, an Eulerian column from its profiles; and what is
//! refused, by name.

mod common;

use std::path::{Path, PathBuf};

use common::*;

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes/small_dem_bed.toml")
}

/// Run the small DEM bed (86 grains, 0.1 s of deposition, 0.02 s of flow) into a fresh
/// folder `name` with `args` after the scene: the folder.
fn run(name: &str, args: &[&str]) -> PathBuf {
    let s = scene();
    let out = tmp_dir(name);
    let mut a = vec!["run", s.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    a.extend(args);
    let o = saltus(&a);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

/// `column` of the first and the last row of a run's time series.
fn first_last(dir: &Path, column: &str) -> (f64, f64) {
    let (h, rows) = read_table(&dir.join("timeseries.csv"));
    let v = |r: &[String]| cell(&h, r, column).parse::<f64>().unwrap();
    (v(&rows[0]), v(rows.last().unwrap()))
}

/// From a DEM run of the same case: no deposition, the parent's grains moving and its
/// fluid column as it left it (the first row's Shields number, read off the column, is
/// the parent's last, where a start from rest has none). The same grains under another
/// slope take the grains and a column at rest.
#[test]
fn a_dem_run_from_a_developed_state_of_its_case_starts_with_its_grains_and_its_fluid() {
    let parent = run("warm_parent", &[]);
    let child = run("warm_child", &["--warm-start", parent.to_str().unwrap()]);
    let (p, c) = (summary(&parent), summary(&child));
    assert!(p["total_steps"].as_u64() > p["steps"].as_u64(), "the parent deposits its bed");
    assert_eq!(c["total_steps"], c["steps"], "no deposition: {c}");
    let (parent_first, parent_last) = first_last(&parent, "shields");
    assert_eq!(parent_first, 0.0, "from rest the fluid starts at rest");
    let (child_first, _) = first_last(&child, "shields");
    assert!(
        parent_last > 0.0 && (child_first - parent_last).abs() <= 1e-12 * parent_last,
        "{child_first} {parent_last}"
    );
    assert!(first_last(&child, "qs").0 > 0.0, "the carried grains move");

    let steeper = run("warm_child_slope", &["--warm-start", parent.to_str().unwrap(), "--set", "physics.slope=0.12"]);
    let s = summary(&steeper);
    assert_eq!(s["total_steps"], s["steps"], "the grains are carried: {s}");
    assert_eq!(first_last(&steeper, "shields").0, 0.0, "another forcing: the column starts at rest");
    assert!(first_last(&steeper, "qs").0 > 0.0);
}

/// From a two-fluid run of the same bed: the grains are deposited as from rest, then move
/// with the run's u_p (the first row's rate, zero from rest, is not) and the fluid column
/// takes its u_f.
#[test]
fn a_dem_run_from_a_two_fluid_run_deposits_its_grains_and_takes_its_velocities() {
    let two_fluid = run(
        "warm_two_fluid",
        &[
            "--set",
            "solver.type=eulerian",
            "--set",
            "closures.granular.type=mu_i",
            "--set",
            "solver.eulerian.end_time=200",
        ],
    );
    assert_eq!(summary(&two_fluid)["solver"], "eulerian");
    let rest = run("warm_rest", &[]);
    let warm = run("warm_from_two_fluid", &["--warm-start", two_fluid.to_str().unwrap()]);
    let (r, w) = (summary(&rest), summary(&warm));
    assert_eq!(w["total_steps"], r["total_steps"], "the same deposition, then the flow");
    assert_eq!(first_last(&rest, "qs").0, 0.0);
    assert!(first_last(&warm, "qs").0 > 0.0, "the grains start with the two-fluid u_p");
    // the carried fluid drives the bed: at the end of 0.02 s of flow far above the start
    // from rest (its column still accelerating)
    assert!(first_last(&warm, "shields").1 > 100.0 * first_last(&rest, "shields").1);
}

/// An Eulerian column from its own steady state is steady in a fifth of the steps or
/// fewer (the time step still grows from its first; measured 43 against 364), with the
/// same rate (the steady state is the column's fixed point; to the steady tolerance).
#[test]
fn an_eulerian_run_from_its_own_steady_state_is_steady_at_once_with_the_same_rate() {
    let set = ["--set", "solver.type=eulerian", "--set", "closures.granular.type=mu_i"];
    let first = run("warm_eulerian_first", &set);
    let mut args = set.to_vec();
    args.extend(["--warm-start", first.to_str().unwrap()]);
    let again = run("warm_eulerian_again", &args);
    let (a, b) = (summary(&first), summary(&again));
    assert_eq!(a["ending"], "steady");
    assert_eq!(b["ending"], "steady");
    assert!(b["steps"].as_u64().unwrap() * 5 < a["steps"].as_u64().unwrap(), "{} then {}", a["steps"], b["steps"]);
    let (qa, qb) = (a["qs_star"].as_f64().unwrap(), b["qs_star"].as_f64().unwrap());
    assert!((qa - qb).abs() < 1e-5 * qa, "{qa} then {qb}");
}

/// Refused by name, before anything is written: a folder that does not exist, a run
/// folder without the state the scene needs, a DEM run of other grains (the keys named),
/// and a continued run (`--restart` goes on from its own checkpoint).
#[test]
fn warm_starts_that_cannot_be_taken_are_refused_by_name() {
    let s = scene();
    let s = s.to_str().unwrap();
    let out = tmp_dir("warm_refused_out");
    let out = out.to_str().unwrap();
    let missing = assert_clean_failure(&saltus(&["run", s, "--out", out, "--warm-start", "/nonexistent/run"]));
    assert!(missing.contains("--warm-start") && missing.contains("/nonexistent/run"), "{missing}");

    let empty = tmp_dir("warm_refused_empty");
    let no_state = assert_clean_failure(&saltus(&["run", s, "--out", out, "--warm-start", empty.to_str().unwrap()]));
    assert!(no_state.contains("--warm-start") && no_state.contains("checkpoint"), "{no_state}");
    let eulerian = assert_clean_failure(&saltus(&[
        "run",
        s,
        "--out",
        out,
        "--set",
        "solver.type=eulerian",
        "--set",
        "closures.granular.type=mu_i",
        "--warm-start",
        empty.to_str().unwrap(),
    ]));
    assert!(eulerian.contains("no profiles to start from"), "{eulerian}");

    let parent = run("warm_refused_parent", &[]);
    let other = assert_clean_failure(&saltus(&[
        "run",
        s,
        "--out",
        out,
        "--set",
        "particles.diameter=5e-3",
        "--warm-start",
        parent.to_str().unwrap(),
    ]));
    assert!(other.contains("other grains") && other.contains("particles.diameter"), "{other}");
    let restart = assert_clean_failure(&saltus(&[
        "run",
        s,
        "--restart",
        parent.to_str().unwrap(),
        "--warm-start",
        parent.to_str().unwrap(),
    ]));
    assert!(restart.contains("--warm-start") && restart.contains("--restart"), "{restart}");
}
