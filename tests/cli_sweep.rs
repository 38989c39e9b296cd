//! `saltus sweep` through the command line: the shipped Chassagne theta sweep against its
//! case files, resuming, emitting and collecting, seed ensembles, and bad sweep files
//! refused before any run.

mod common;

use std::path::{Path, PathBuf};

use common::*;

const THETA_SWEEP: &str = "cases/chassagne2023/theta_sweep.toml";

fn qs_star(dir: &Path) -> f64 {
    summary(dir)["qs_star"].as_f64().unwrap_or_else(|| panic!("{}: no qs_star", dir.display()))
}

/// A sweep over case 2's scene (theta = 0.2 set through the Shields number, cells of
/// d/4) with `axes` (TOML text).
fn case02_sweep(dir: &Path, name: &str, axes: &str) -> PathBuf {
    let case02 = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/chassagne2023/case02.toml");
    write(
        dir,
        name,
        &format!(
            "base = {:?}\nset = ['physics.shields=0.2', 'physics.drive=\"water_depth\"', 'physics.shields_weight=\"vertical\"', 'domain.cell_size=\"d/4\"']\nunset = [\"domain.water_depth\", \"domain.cells\"]\n{axes}",
            case02.display().to_string()
        ),
    )
}

/// The shipped sweep is the case files: the same qs* as cases 2, 3, 1, 4, 5 run one by
/// one, to 1e-9 (the water depths set from theta differ from the files' by rounding).
#[test]
fn the_chassagne_theta_sweep_gives_the_qs_star_of_its_case_files() {
    let d = tmp_dir("sweep_chassagne_theta");
    let out = d.join("sweep");
    let o = saltus(&["sweep", THETA_SWEEP, "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = read_table(&out.join("sweep.csv"));
    assert_eq!(rows.len(), 5);
    for (k, case) in ["02", "03", "01", "04", "05"].iter().enumerate() {
        let run = d.join(format!("case{case}"));
        let file = format!("cases/chassagne2023/case{case}.toml");
        let r = saltus(&["run", &file, "--out", run.to_str().unwrap(), "--quiet"]);
        assert!(r.status.success(), "{}", stderr(&r));
        let want = qs_star(&run);
        let got: f64 = cell(&header, &rows[k], "qs_star").parse().unwrap();
        assert!((got - want).abs() <= 1e-9 * want, "case {case}: sweep {got}, case file {want}");
        assert_eq!(cell(&header, &rows[k], "cells"), summary(&run)["cells"].to_string(), "case {case}");
        assert_eq!(cell(&header, &rows[k], "status"), "done");
    }
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    for p in manifest["points"].as_array().unwrap() {
        assert_eq!(p["status"], "done", "{p}");
        assert_eq!(p["scene_hash"].as_str().map(str::len), Some(16), "{p}");
        assert!(p["wall_time_s"].as_f64().is_some_and(|w| w > 0.0), "{p}");
    }
    assert!(out.join("sweep.png").is_file());
}

/// A sweep whose point was killed while it ran (left `running` in the manifest, without
/// its summary) continues with `--resume`: the finished points are kept as they are and
/// only the lost one runs again, to the same answer.
#[test]
fn a_resumed_sweep_runs_only_the_points_that_did_not_finish() {
    let d = tmp_dir("sweep_resume");
    let file = case02_sweep(&d, "s.toml", "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2, 0.3, 0.4]\n");
    let out = d.join("out");
    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let kept: Vec<String> = [0, 2]
        .iter()
        .map(|i| std::fs::read_to_string(out.join(format!("point_000{i}/summary.json"))).unwrap())
        .collect();
    let lost = qs_star(&out.join("point_0001"));
    let m = out.join("sweep.json");
    let text = std::fs::read_to_string(&m).unwrap();
    let mut manifest: serde_json::Value = serde_json::from_str(&text).unwrap();
    manifest["points"][1]["status"] = "running".into();
    std::fs::write(&m, serde_json::to_string_pretty(&manifest).unwrap()).unwrap();
    std::fs::remove_file(out.join("point_0001/summary.json")).unwrap();

    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--resume"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("3 points (1 run now, 2 kept)"), "{}", stdout(&o));
    for (k, i) in [0, 2].iter().enumerate() {
        let now = std::fs::read_to_string(out.join(format!("point_000{i}/summary.json"))).unwrap();
        assert_eq!(now, kept[k], "point {i} was run again");
    }
    assert_eq!(qs_star(&out.join("point_0001")), lost);
    let (header, rows) = read_table(&out.join("sweep.csv"));
    assert!(rows.iter().all(|r| cell(&header, r, "status") == "done"), "{rows:?}");
}

#[test]
fn resume_refuses_a_folder_of_another_sweep() {
    let d = tmp_dir("sweep_resume_other");
    let a = case02_sweep(&d, "a.toml", "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2]\n");
    let b = case02_sweep(&d, "b.toml", "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.3]\n");
    let out = d.join("out");
    let o = saltus(&["sweep", a.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read_to_string(out.join("sweep.json")).unwrap();
    let o = saltus(&["sweep", b.to_str().unwrap(), "--out", out.to_str().unwrap(), "--resume"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("sweep.json") && err.contains("another sweep") && err.contains("a.toml"), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("sweep.json")).unwrap(), before, "the folder is left as it was");
    // a folder that holds something else than a sweep
    let other = d.join("other");
    std::fs::create_dir_all(&other).unwrap();
    write(&other, "summary.json", "{}");
    let o = saltus(&["sweep", a.to_str().unwrap(), "--out", other.to_str().unwrap(), "--resume"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("not a sweep's folder"), "{err}");
}

/// `--emit` writes scenes that `saltus run` runs as they are (a job array's work) and
/// `--collect` gathers them into the table an in-process sweep writes.
#[test]
fn emitted_points_run_alone_and_collect_into_the_same_table() {
    let d = tmp_dir("sweep_emit");
    let file = case02_sweep(&d, "s.toml", "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2, 0.4]\n");
    let jobs = d.join("jobs");
    let o = saltus(&["sweep", file.to_str().unwrap(), "--emit", jobs.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for i in 0..2 {
        let scene = jobs.join(format!("point_000{i}.toml"));
        let r = saltus(&["run", scene.to_str().unwrap(), "--quiet"]);
        assert!(r.status.success(), "{}", stderr(&r));
    }
    let o = saltus(&["sweep", file.to_str().unwrap(), "--collect", jobs.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let here = d.join("here");
    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", here.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (h1, r1) = read_table(&jobs.join("sweep.csv"));
    let (h2, r2) = read_table(&here.join("sweep.csv"));
    assert_eq!(h1, h2, "the same columns, collected or run here");
    for name in &h1 {
        assert_eq!(h1.iter().filter(|c| *c == name).count(), 1, "column {name} once: {h1:?}");
    }
    for k in 0..2 {
        assert_eq!(cell(&h1, &r1[k], "status"), "done");
        assert_eq!(cell(&h1, &r1[k], "qs_star"), cell(&h2, &r2[k], "qs_star"), "point {k}");
        // the collected point's cost is its run's, from its summary
        let run = summary(&jobs.join(format!("point_000{k}")));
        for clock in ["cpu_time_s", "wall_time_s"] {
            let got: f64 = cell(&h1, &r1[k], clock).parse().unwrap();
            assert_eq!(Some(got), run[clock].as_f64(), "point {k}, {clock}");
        }
    }
}

/// A seed axis pools each point's seeds. The Eulerian column draws nothing at random,
/// so every seed gives the same run: the pooled mean is that run's qs* and the spread
/// across seeds zero.
#[test]
fn a_seed_axis_pools_the_seeds_of_each_point() {
    let d = tmp_dir("sweep_seeds");
    let file = case02_sweep(
        &d,
        "s.toml",
        "[[axis]]\nkey = \"physics.shields\"\nname = \"theta\"\nvalues = [0.2, 0.4]\n[[axis]]\nkey = \"seed\"\nvalues = [1, 2, 3]\n",
    );
    let out = d.join("out");
    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (h, rows) = read_table(&out.join("sweep.csv"));
    assert_eq!(rows.len(), 6);
    assert_eq!((cell(&h, &rows[0], "theta"), cell(&h, &rows[0], "seed")), ("0.2", "1"));
    assert_eq!((cell(&h, &rows[5], "theta"), cell(&h, &rows[5], "seed")), ("0.4", "3"));
    let (hs, pooled) = read_table(&out.join("sweep_seeds.csv"));
    assert_eq!(pooled.len(), 2);
    for (k, r) in pooled.iter().enumerate() {
        assert_eq!(cell(&hs, r, "seeds"), "3");
        let one: f64 = cell(&h, &rows[3 * k], "qs_star").parse().unwrap();
        let mean: f64 = cell(&hs, r, "qs_star").parse().unwrap();
        assert!((mean - one).abs() <= 1e-15 * one, "{mean} against {one}");
        assert_eq!(cell(&hs, r, "qs_star_seed_sem").parse::<f64>().unwrap(), 0.0);
    }
}

/// Each bad sweep is refused before any run (no output folder), naming the file and
/// the key.
#[test]
fn bad_sweeps_are_refused_naming_the_file_and_the_key() {
    let d = tmp_dir("sweep_bad");
    let cases: [(&str, &str, &[&str]); 8] = [
        ("unknown_key", "[[axis]]\nkey = \"physics.shieldz\"\nvalues = [0.2]\n", &["axis[0].key", "shieldz"]),
        (
            "unknown_closure_key",
            "[[axis]]\nkey = \"closures.drag.exponent\"\nvalues = [2.0]\n",
            &["axis[0].key", "exponent"],
        ),
        ("empty", "[[axis]]\nkey = \"physics.shields\"\nvalues = []\n", &["axis[0].values", "empty"]),
        ("nan", "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2, nan]\n", &["axis[0].values[1]", "finite"]),
        ("bad_linspace", "[[axis]]\nkey = \"physics.shields\"\nlinspace = [0.2, inf, 3]\n", &["axis[0].linspace"]),
        (
            "zip",
            "combine = \"zip\"\n[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2, 0.3]\n[[axis]]\nkey = \"seed\"\nvalues = [1]\n",
            &["axis[1]", "equal length"],
        ),
        (
            "lid",
            "[[axis]]\nkey = \"domain.top\"\nvalues = [\"lid\"]\n",
            &["physics.drive", "lid"],
        ),
        (
            "where",
            "[[axis]]\nkey = \"physics.shields\"\nname = \"theta\"\nvalues = [0.2]\n[[point]]\nwhere = { theta = 0.5 }\nset = []\n",
            &["point[0].where.theta", "not a value"],
        ),
    ];
    for (name, axes, words) in cases {
        let file = case02_sweep(&d, &format!("{name}.toml"), axes);
        let out = d.join(format!("out_{name}"));
        let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let err = assert_clean_failure(&o);
        assert!(err.contains(&format!("{name}.toml")) || err.contains("case02.toml"), "{name}: {err}");
        for w in words {
            assert!(err.contains(w), "{name}: `{w}` not in {err}");
        }
        assert!(!out.exists(), "{name}: the output folder was made");
    }
}

/// SIGINT while a point runs: the finished point is kept, the running one writes its
/// state and is marked interrupted, none other starts, the exit code is 130; `--resume`
/// then runs only the points that did not finish.
#[cfg(unix)]
#[test]
fn an_interrupted_sweep_keeps_its_finished_points_and_resumes() {
    let d = tmp_dir("sweep_interrupt");
    // points that never reach the steady criterion and run to their end time, one at a
    // time, so that the second is running when the first has finished
    let file = case02_sweep(
        &d,
        "s.toml",
        "jobs = 1\n[[axis]]\nkey = \"solver.eulerian.end_time\"\nvalues = [3.0e4, 3.1e4, 3.2e4, 3.3e4]\n[[axis]]\nkey = \"solver.eulerian.steady_tolerance\"\nvalues = [1e-30]\n",
    );
    let out = d.join("out");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let first = out.join("point_0000/summary.json");
    while !first.is_file() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the sweep ended before its first point did: {status:?}");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let kill = std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("--resume"), "{}", stderr(&o));
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    let status: Vec<&str> =
        manifest["points"].as_array().unwrap().iter().map(|p| p["status"].as_str().unwrap()).collect();
    assert_eq!(status[0], "done", "{status:?}");
    // the second point was running (or had just finished, or not yet started when the
    // signal came between the two) and the rest never started
    assert!(matches!(status[1], "interrupted" | "done" | "pending"), "{status:?}");
    assert!(status[2..].iter().all(|s| *s == "pending"), "{status:?}");
    if status[1] == "interrupted" {
        assert_eq!(summary(&out.join("point_0001"))["ending"], "interrupted");
    }
    let kept = std::fs::read_to_string(&first).unwrap();
    let wall_before = manifest["points"][1]["wall_time_s"].as_f64();
    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--resume"]);
    assert!(o.status.success(), "{}", stderr(&o));
    if status[1] == "interrupted" && out.join("point_0001/checkpoint.bin").is_file() {
        // a continued point's cost counts what it ran before the interrupt
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
        let (before, after) = (wall_before.unwrap(), m["points"][1]["wall_time_s"].as_f64().unwrap());
        assert!(after > before, "wall time {after} s after the resume, {before} s before it");
    }
    assert_eq!(std::fs::read_to_string(&first).unwrap(), kept, "the finished point was run again");
    let (h, rows) = read_table(&out.join("sweep.csv"));
    assert!(rows.iter().all(|r| cell(&h, r, "status") == "done" && cell(&h, r, "ending") == "end_time"), "{rows:?}");
}

/// The shipped DEM sweeps load whole (every point's scene resolved and checked, nothing
/// run): figure 6's Shields numbers give the water depths h_w = 15 theta d of the
/// bed-normal definition and the fluid cells of the hand-written depth list
/// (sweep3d_drw.toml); table 4's points carry their own averaging windows.
#[test]
fn the_shipped_dem_sweeps_resolve_to_the_hand_written_points() {
    let d = tmp_dir("sweep_shipped_dem");
    let fig6 = d.join("fig6");
    let o = saltus(&["sweep", "cases/maurin2015/figure6_sweep.toml", "--emit", fig6.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let hand: toml::Table = std::fs::read_to_string("cases/maurin2015/sweep3d_drw.toml").unwrap().parse().unwrap();
    let hand_cells: Vec<(f64, i64)> = hand["variant"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            let set: Vec<&str> = v["set"].as_array().unwrap().iter().map(|s| s.as_str().unwrap()).collect();
            let num = |k: &str| set.iter().find_map(|s| s.strip_prefix(k)).unwrap().to_string();
            (num("domain.water_depth=").parse().unwrap(), num("solver.lagrangian.cells=").parse().unwrap())
        })
        .collect();
    let thetas = [0.03, 0.04, 0.05, 0.07, 0.08, 0.09, 0.1, 0.12, 0.15, 0.2, 0.3];
    let mut matched = 0;
    for (k, fluct) in ["drw", "none"].iter().enumerate() {
        for (j, theta) in thetas.iter().enumerate() {
            let f = fig6.join(format!("point_{:04}.toml", k * thetas.len() + j));
            let s: toml::Table = std::fs::read_to_string(&f).unwrap().parse().unwrap();
            let h = s["domain"]["water_depth"].as_float().unwrap();
            assert!((h - 15.0 * theta * 6e-3).abs() < 1e-12, "{}: {h}", f.display());
            assert_eq!(s["closures"]["fluctuation"]["type"].as_str(), Some(*fluct));
            let cells = s["solver"]["lagrangian"]["cells"].as_integer().unwrap();
            if let Some((_, c)) = hand_cells.iter().find(|(w, _)| (w - h).abs() < 1e-12) {
                assert_eq!(cells, *c, "{}", f.display());
                matched += 1;
            }
        }
    }
    assert_eq!(matched, 2 * 8, "the eight depths of sweep3d_drw.toml among the eleven");
    // its warm-started copy: the same points, each warm point's window 5-55 s, the first
    // of each series (from rest) 10-55 s
    let warm = d.join("fig6_warm");
    let o = saltus(&["sweep", "cases/maurin2015/figure6_sweep_warm.toml", "--emit", warm.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (k, theta) in thetas.iter().enumerate() {
        let read = |name: &Path| -> toml::Table { std::fs::read_to_string(name).unwrap().parse().unwrap() };
        let cold = read(&fig6.join(format!("point_{k:04}.toml")));
        let hot = read(&warm.join(format!("point_{k:04}.toml")));
        assert_eq!(hot["domain"]["water_depth"].as_float(), cold["domain"]["water_depth"].as_float());
        assert_eq!(
            hot["solver"]["lagrangian"]["cells"].as_integer(),
            cold["solver"]["lagrangian"]["cells"].as_integer()
        );
        assert_eq!(hot["solver"]["lagrangian"]["end_time"].as_float(), Some(55.0));
        let start = if *theta == 0.03 { 10.0 } else { 5.0 };
        assert_eq!(hot["solver"]["lagrangian"]["stats_start"].as_float(), Some(start), "theta {theta}");
    }
    let t4 = d.join("t4");
    let o = saltus(&["sweep", "cases/revil_baudard2015/table4.toml", "--emit", t4.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // with the EIM 100-150 s; without it 200-300 s, and 300-450 s at the table's theta 1.0
    // and 1.2 (the last two gradients)
    for k in 0..14 {
        let s: toml::Table = std::fs::read_to_string(t4.join(format!("point_{k:04}.toml"))).unwrap().parse().unwrap();
        let l = &s["solver"]["lagrangian"];
        let window = (l["stats_start"].as_float().unwrap(), l["end_time"].as_float().unwrap());
        let eim = s["closures"]["fluctuation"]["type"].as_str() == Some("eim");
        let expect = match (eim, k / 2) {
            (true, _) => (100.0, 150.0),
            (false, 5 | 6) => (300.0, 450.0),
            (false, _) => (200.0, 300.0),
        };
        assert_eq!(window, expect, "point {k}, eim {eim}");
        if k == 0 {
            assert_eq!(s["physics"]["pressure_gradient"].as_float(), Some(11.7007));
        }
    }
    assert_eq!(
        std::fs::read_dir(&t4)
            .unwrap()
            .filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "toml"))
            .count(),
        14,
        "table 4's seven Shields numbers with and without the EIM"
    );
}

/// Warm starts: each Eulerian point after the first starts from its neighbour's final
/// profiles, reaches the same steady state (the steady criterion's 1e-6 of qs*, here to
/// 1e-5) in fewer steps, and gives the same numbers on one job as on two (the chain of
/// neighbours fixes which state each point starts from).
#[test]
fn warm_started_points_reach_the_same_steady_state_in_fewer_steps() {
    let d = tmp_dir("sweep_warm");
    let axes = "[[axis]]\nkey = \"physics.shields\"\nvalues = [0.2, 0.4, 0.6, 0.8]\n";
    let cold = case02_sweep(&d, "cold.toml", axes);
    let warm = case02_sweep(&d, "warm.toml", &format!("warm_start = true\n{axes}"));
    let run = |file: &Path, out: &str, jobs: &str| {
        let o =
            saltus(&["sweep", file.to_str().unwrap(), "--out", d.join(out).to_str().unwrap(), "--jobs", jobs, "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        read_table(&d.join(out).join("sweep.csv"))
    };
    let (hc, rc) = run(&cold, "cold", "2");
    let (hw, rw) = run(&warm, "warm", "2");
    let (h1, r1) = run(&warm, "warm1", "1");
    let num = |h: &[String], r: &[String], c: &str| cell(h, r, c).parse::<f64>().unwrap();
    let (mut steps_cold, mut steps_warm) = (0.0, 0.0);
    for k in 0..4 {
        assert_eq!(cell(&hw, &rw[k], "status"), "done");
        assert_eq!(cell(&hw, &rw[k], "ending"), "steady");
        let from = cell(&hw, &rw[k], "warm_start_from");
        assert_eq!(from, if k == 0 { String::new() } else { format!("point_{:04}", k - 1) });
        let (qc, qw) = (num(&hc, &rc[k], "qs_star"), num(&hw, &rw[k], "qs_star"));
        assert!((qw - qc).abs() <= 1e-5 * qc, "point {k}: warm {qw}, cold {qc}");
        assert_eq!(cell(&hw, &rw[k], "qs_star"), cell(&h1, &r1[k], "qs_star"), "point {k}: two jobs against one");
        steps_cold += num(&hc, &rc[k], "steps");
        steps_warm += num(&hw, &rw[k], "steps");
    }
    assert!(steps_warm < steps_cold, "{steps_warm} steps warm, {steps_cold} cold");
}
