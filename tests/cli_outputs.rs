//! What `saltus run` writes while it runs and when it is stopped: the time series, the
//! snapshots, a DEM interrupted by SIGTERM or SIGINT in the deposition and in the flow
//! (exit 130, outputs and a checkpoint written, `--restart` finishes it), `--json`,
//! `--quiet`, the exit code of an unstable run, and `check` refusing bad `[output]` keys.

mod common;

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use common::*;

/// A DEM bed of about a hundred grains (6 x 6 diameters, three diameters deep) that
/// deposits for 0.3 s of simulated time before it flows.
const SMALL_DEM: [&str; 16] = [
    "--set",
    "solver.type=\"lagrangian\"",
    "--set",
    "solver.lagrangian.length=0.036",
    "--set",
    "solver.lagrangian.width=0.036",
    "--set",
    "domain.bed_height=0.018",
    "--set",
    "domain.water_depth=0.03",
    "--set",
    "solver.lagrangian.settle_time=0.3",
    "--set",
    "solver.lagrangian.stats_start=0.0",
    "--set",
    "output.snapshot_interval=0.01",
];

fn dem_args<'a>(out: &'a str, end_time: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut a = vec!["run", CASE01];
    a.extend(SMALL_DEM);
    a.extend(["--set", end_time, "--out", out]);
    a.extend(extra);
    a
}

/// No NaN or infinity in any CSV or JSON the run wrote.
fn assert_all_finite(dir: &Path) {
    let mut files = vec![];
    for d in [dir.to_path_buf(), dir.join("snapshots")] {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if matches!(p.extension().and_then(|x| x.to_str()), Some("csv" | "json")) {
                files.push(p);
            }
        }
    }
    assert!(files.len() >= 3, "{files:?}");
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap().to_lowercase();
        assert!(!text.contains("nan") && !text.contains("inf"), "{}: {text}", f.display());
    }
}

/// Start a DEM run, wait for its first progress line of `phase` (one every 0.1 s of wall
/// time), send `signal`, and return its exit code and stderr.
fn interrupt(out: &Path, phase: &str, signal: &str) -> (Option<i32>, String) {
    let o = out.to_str().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(dem_args(o, "solver.lagrangian.end_time=1000.0", &["--log-interval", "0.1"]))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run saltus");
    let stderr = child.stderr.take().expect("stderr");
    let (tx, rx) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let mut err = String::new();
    let want = format!("] {phase} t = ");
    loop {
        match rx.recv_timeout(Duration::from_secs(120)) {
            Ok(line) => {
                err.push_str(&line);
                err.push('\n');
                if line.contains(&want) {
                    break;
                }
            }
            Err(_) => {
                let _ = child.kill();
                panic!("no `{phase}` progress line: {err}");
            }
        }
    }
    // the folder and the time series exist from the start of the run
    assert!(out.join("timeseries.csv").is_file(), "{err}");
    let sent = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().expect("kill");
    assert!(sent.success());
    let status = child.wait().expect("wait");
    let _ = reader.join();
    err.extend(rx.try_iter().map(|l| l + "\n"));
    (status.code(), err)
}

/// After an interrupt: exit 130, the outputs of the state so far, a checkpoint, nothing
/// non-finite; returns the summary.
fn assert_interrupted(out: &Path, code: Option<i32>, err: &str) -> serde_json::Value {
    assert_eq!(code, Some(130), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains("interrupted at t = ") && err.contains("--restart"), "{err}");
    for f in ["profiles.csv", "summary.json", "scene.toml", "manifest.json", "timeseries.csv", "checkpoint.bin"] {
        assert!(out.join(f).is_file(), "{f} missing: {err}");
    }
    assert_all_finite(out);
    let s = summary(out);
    assert_eq!(s["ending"].as_str(), Some("interrupted"), "{s}");
    s
}

fn restart(out: &Path, end_time: &str) -> serde_json::Value {
    let o = out.to_str().unwrap();
    let r = saltus(&dem_args(o, end_time, &["--restart", o]));
    assert!(r.status.success(), "{}", stderr(&r));
    let s = summary(out);
    assert_eq!(s["ending"].as_str(), Some("end_time"), "{s}");
    assert_all_finite(out);
    s
}

#[test]
fn sigterm_during_the_deposition_writes_a_checkpoint_that_restarts() {
    let d = tmp_dir("interrupt_deposition_term");
    let (code, err) = interrupt(&d, "deposition", "TERM");
    let s = assert_interrupted(&d, code, &err);
    // stopped before the flow: no flow step, no row
    assert_eq!(s["steps"].as_u64(), Some(0), "{s}");
    assert_eq!(
        std::fs::read_to_string(d.join("timeseries.csv")).unwrap(),
        "t,qs,qs_star,shields,bed_surface,residual,steps,theta_g\n"
    );
    let s = restart(&d, "solver.lagrangian.end_time=0.02");
    assert!(s["steps"].as_u64().is_some_and(|n| n > 0), "{s}");
    let (header, rows) = read_table(&d.join("timeseries.csv"));
    assert_eq!(header, ["t", "qs", "qs_star", "shields", "bed_surface", "residual", "steps", "theta_g"]);
    assert!(rows.len() >= 2 && cell(&header, &rows[0], "t").parse::<f64>() == Ok(0.0), "{rows:?}");
}

#[test]
fn sigint_during_the_flow_writes_the_state_so_far_and_a_restart_finishes() {
    let d = tmp_dir("interrupt_flow_int");
    let (code, err) = interrupt(&d, "flow", "INT");
    let s = assert_interrupted(&d, code, &err);
    let t = s["sim_time_s"].as_f64().expect("time");
    assert!(t > 0.0, "{s}");
    let (header, rows) = read_table(&d.join("timeseries.csv"));
    let last: f64 = cell(&header, rows.last().expect("rows"), "t").parse().expect("t");
    assert!((last - t).abs() < 1e-6, "the last row is the state written: {last} vs {t}");
    // the end time may change on a restart: 0.02 s more
    let s = restart(&d, &format!("solver.lagrangian.end_time={}", t + 0.02));
    assert!(s["sim_time_s"].as_f64().is_some_and(|x| x >= t + 0.02 - 1e-4), "{s}");
    assert!(d.join("snapshots/index.csv").is_file() && d.join("snapshots/profiles_00000.csv").is_file());
}

#[test]
fn sigterm_during_the_flow_stops_it_too() {
    let d = tmp_dir("interrupt_flow_term");
    let (code, err) = interrupt(&d, "flow", "TERM");
    assert_interrupted(&d, code, &err);
}

#[test]
fn json_prints_the_summary_alone_and_quiet_prints_nothing() {
    let d = tmp_dir("run_json_quiet");
    let o = saltus(&["run", CASE01, "--set", "domain.cells=60", "--out", d.to_str().unwrap(), "--json", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    let s: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("stdout is the summary as JSON");
    assert_eq!(s, summary(&d));
    // the Eulerian writes its time series too: a row at t = 0, rows on the cadence, the end
    let (header, rows) = read_table(&d.join("timeseries.csv"));
    let t: Vec<f64> = rows.iter().map(|r| cell(&header, r, "t").parse().unwrap()).collect();
    assert!(t[0] == 0.0 && t.windows(2).all(|w| w[1] > w[0]), "{t:?}");
    assert_eq!(cell(&header, rows.last().unwrap(), "steps"), s["steps"].to_string());
    assert!(rows.len() > 3 && rows.len() <= 1002, "{}", rows.len());
    assert_all_finite(&d);
    let o = saltus(&["run", CASE01, "--set", "domain.cells=60", "--out", d.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success() && stdout(&o).is_empty() && stderr(&o).is_empty(), "{}", stderr(&o));
}

#[test]
fn check_refuses_bad_output_intervals_as_run_does() {
    for (set, key) in [
        ("output.timeseries_interval=0", "output.timeseries_interval"),
        ("output.snapshot_interval=-1", "output.snapshot_interval"),
        ("output.checkpoint_interval=1e-9", "output.checkpoint_interval"),
        ("output.snapshot_interval=\"often\"", "output.snapshot_interval"),
    ] {
        for cmd in ["check", "run"] {
            let o = saltus(&[cmd, CASE01, "--set", set]);
            let err = assert_clean_failure(&o);
            assert!(err.contains("case01.toml") && err.contains(key), "{cmd} {set}: {err}");
        }
    }
    let o = saltus(&["check", CASE01, "--set", "output.checkpoint_interval=1e-9"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("0 (off) or at least solver.eulerian.end_time / 1e5"), "{err}");
    let o = saltus(&["check", CASE01]);
    // the default interval is resolved: the end time over 1000
    let text = stdout(&o);
    let value = |key: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with(&format!("{key} = "))).unwrap_or_else(|| panic!("{text}"));
        line[key.len() + 3..].parse().unwrap()
    };
    assert_eq!(value("timeseries_interval"), value("end_time") / 1000.0, "{text}");
    assert_eq!(value("snapshot_interval"), 0.0);
    let o = saltus(&["run", CASE01, "--restart", "no/such/dir", "--quiet"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("no/such/dir"), "{err}");
}

#[test]
fn an_interrupted_compare_exits_130() {
    // case 1 in both solvers: the DEM variant runs for minutes, the interrupt stops it
    let d = tmp_dir("compare_interrupted");
    let child = Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(["compare", "cases/chassagne2023/compare_case01_solvers.toml", "--out", d.to_str().unwrap()])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run saltus");
    // the variants' folders appear when their runs start
    let start = std::time::Instant::now();
    while std::fs::read_dir(&d).map_or(0, |r| r.count()) < 2 && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(500));
    let sent = Command::new("kill").args(["-INT", &child.id().to_string()]).status().expect("kill");
    assert!(sent.success());
    let o = child.wait_with_output().expect("wait");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted") && !err.contains("panicked"), "{err}");
}

#[test]
fn a_restart_that_switches_the_vtk_snapshots_on_writes_one_per_period() {
    // the snapshot clock starts at 0 with the run: on a restart at t = 0.1 s it must not
    // write one snapshot per fluid update (0.01 s) until it catches up
    let d = tmp_dir("restart_vtk_on");
    let o = d.to_str().unwrap();
    let r = saltus(&dem_args(o, "solver.lagrangian.end_time=0.1", &[]));
    assert!(r.status.success(), "{}", stderr(&r));
    let r = saltus(&dem_args(
        o,
        "solver.lagrangian.end_time=0.16",
        &["--set", "solver.lagrangian.vtk_period=0.02", "--restart", o],
    ));
    assert!(r.status.success(), "{}", stderr(&r));
    let pvd = std::fs::read_to_string(d.join("vtk").join("series.pvd")).unwrap();
    let times: Vec<f64> = pvd
        .lines()
        .filter(|l| l.starts_with("<DataSet") && l.contains("part=\"0\""))
        .map(|l| l.split("timestep=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap())
        .collect();
    // 0.1 s to 0.16 s at one snapshot per 0.02 s: 3, at fluid updates 0.01 s apart
    assert!((2..=4).contains(&times.len()), "{times:?}");
    assert!(times.windows(2).all(|w| w[1] - w[0] > 0.015), "{times:?}");
}
