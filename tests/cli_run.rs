//! `saltus run` through the command line: its outputs and figure, reference data, a
//! breakdown keeping the outputs, and a stderr that cannot be written (interrupts are in
//! `cli_outputs.rs`).

mod common;

use std::process::Command;

use common::*;

#[test]
fn run_writes_outputs_and_the_profile_figure() {
    let d = tmp_dir("run_case01");
    let o = saltus(&["run", CASE01, "--set", "domain.cells=60", "--out", d.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["profiles.csv", "summary.json", "scene.toml", "manifest.json"] {
        assert!(d.join(f).is_file(), "{f} missing");
    }
    let s = summary(&d);
    let qs_star = s["qs_star"].as_f64().unwrap();
    assert!(qs_star.is_finite() && qs_star > 0.0, "qs* = {qs_star}");
    assert!(s["mass_error"].as_f64().unwrap().abs() < 1e-10, "{s}");
    assert_eq!(s["cells"].as_u64(), Some(60));
    let csv = std::fs::read_to_string(d.join("profiles.csv")).unwrap();
    assert!(csv.starts_with("z,phi,") && csv.lines().count() == 61, "{}", &csv[..80]);
    assert_png(&d.join("profiles.png"));
    let out = stdout(&o);
    assert!(out.contains("qs*") && out.contains(d.to_str().unwrap()), "{out}");
    assert!(out.contains(d.join("profiles.png").to_str().unwrap()), "{out}");
    // no progress bar when stderr is not a terminal (a line every 10 s of wall time
    // instead, none for a run this short)
    assert!(!stderr(&o).contains('\r') && !stderr(&o).contains("=>"), "{}", stderr(&o));
}

#[test]
fn run_with_a_missing_reference_file_warns_and_succeeds() {
    let d = tmp_dir("run_missing_reference");
    let o = saltus(&[
        "run",
        CASE01,
        "--set",
        "domain.cells=60",
        "--set",
        "reference.file=\"no_such_reference.txt\"",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("warning") && err.contains("no_such_reference.txt"), "{err}");
    assert!(err.contains("reference.file"), "{err}");
    assert_png(&d.join("profiles.png"));
}

#[test]
fn run_that_breaks_down_still_draws_its_last_good_state() {
    // steps of 0.1 s with phi allowed to change by 1e-6 per step: every step is rejected
    // until dt falls under dt_min
    let d = tmp_dir("run_unstable");
    let o = saltus(&[
        "run",
        CASE01,
        "--set",
        "domain.cells=60",
        "--set",
        "solver.eulerian.max_phi_change=1e-6",
        "--set",
        "solver.eulerian.dt_initial=0.1",
        "--set",
        "solver.eulerian.dt_min=0.01",
        "--out",
        d.to_str().unwrap(),
    ]);
    // exit 3: the run stopped, unstable, with its last good state written and reported
    let (err, s) = assert_unstable(&o, &d);
    let stop = err.lines().find(|l| l.starts_with("error:")).unwrap_or_else(|| panic!("{err}"));
    // the breakdown: time, cell, field, and where the outputs are
    assert!(
        stop.contains("unstable at t = ") && stop.contains(" in cell ") && stop.contains(d.to_str().unwrap()),
        "{stop}"
    );
    assert!(s["error"].as_str().is_some_and(|e| e.contains("cell")), "{s}");
    let out = stdout(&o);
    assert!(out.contains("unstable after") && out.contains(d.to_str().unwrap()), "{out}");
    assert_png(&d.join("profiles.png"));
}

#[test]
fn a_dem_run_that_breaks_down_names_the_particle_and_keeps_its_outputs() {
    let d = tmp_dir("run_dem_unstable");
    let o = saltus(&[
        "run",
        "cases/verification/dem_settling.toml",
        "--set",
        "physics.pressure_gradient=1e9",
        "--out",
        d.to_str().unwrap(),
    ]);
    let (err, _) = assert_unstable(&o, &d);
    assert!(err.contains("unstable at t = ") && err.contains("|v|") && err.contains("in particle 0"), "{err}");
    // a fluid at rest has no averaging sample before the first fluid update: no invented
    // transport figures, and nothing non-finite
    for f in ["profiles.csv", "summary.json", "scene.toml", "manifest.json"] {
        assert!(d.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(d.join("profiles.csv")).unwrap();
    assert!(!csv.contains("NaN") && !csv.contains("inf"), "{csv}");
}

#[test]
fn several_reference_files_with_a_z_offset() {
    let d = tmp_dir("reference_array");
    write(&d, "a.txt", "# z phi\n0.0 0.5\n0.01 0.4\n");
    write(&d, "b.txt", "0.0, 1.0\n0.02, 2.0\n");
    let extra = "[[reference]]\nfile = \"a.txt\"\ncolumns = [\"z\", \"phi\"]\nz_offset = 0.04\n\
                 [[reference]]\nfile = \"b.txt\"\ncolumns = [\"z\", \"u_p\"]\n";
    let p = write(&d, "scene.toml", &format!("{BASE}{RUNNABLE}{extra}"));
    let o = saltus(&["check", p.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("z_offset = 0.04"), "{}", stdout(&o));
    saltus_closures::link();
    let scene = saltus_core::scene::Scene::from_file(&p).expect("scene");
    let refs = saltus::runner::load_reference(&scene).expect("reference data");
    assert_eq!(refs.len(), 2);
    assert_eq!(refs[0].1.get("z"), Some(&[0.04, 0.05][..]), "z shifted by z_offset");
    assert_eq!(refs[1].1.get("u_p"), Some(&[1.0, 2.0][..]));
    // a mistake in the second table names its index and the key
    let bad = "[[reference]]\nfile = \"a.txt\"\ncolumns = [\"z\", \"phi\"]\n\
               [[reference]]\nfile = \"b.txt\"\ncolumns = [\"z\", \"u_p\"]\nz_ofset = 1.0\n";
    let p = write(&d, "bad.toml", &format!("{BASE}{bad}"));
    let err = assert_clean_failure(&saltus(&["check", p.to_str().unwrap()]));
    assert!(err.contains("reference[1]") && err.contains("z_ofset") && err.contains("z_offset"), "{err}");
}

#[test]
fn a_full_stderr_loses_the_message_not_the_exit_code() {
    // `2>/dev/full`: every write to stderr fails; the error path must still exit 2
    // (bad input), not panic (101)
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full on Linux");
    let o = Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(["check", "cases/chassagne2023/case01.toml", "--set", "closures.drag={type=\"nope\"}"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stderr(std::process::Stdio::from(full))
        .output()
        .expect("run saltus");
    assert_eq!(o.status.code(), Some(2), "{:?}", o.status);
}
