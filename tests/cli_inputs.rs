//! Accepted input that must neither abort, nor write impossible values, nor touch the
//! user's files, run through the built program: derived DEM cell counts held to their
//! range, the resolved scene that `check` prints accepted by `check`, grains that pass
//! through each other stopped as unstable, a diagnosis of a short Eulerian run, the
//! scene file never overwritten, errors that name the key and not a megabyte of it,
//! paragraphs that name an unnamed scene and never print a zero time, and `--restart`
//! continuing in its own folder. The scenes are in `tests/fixtures/scenes/` or inline.

mod common;

use common::*;
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes").join(name)
}

/// `check` and `run` of `scene` with `set` both refuse it with the same message,
/// which names `key`; the message.
fn refused_alike(name: &str, scene: &Path, set: &[&str], key: &str) -> String {
    let s = scene.to_str().unwrap();
    let mut check = vec!["check", s];
    let out = tmp_dir(name);
    let mut run = vec!["run", s, "--out", out.to_str().unwrap(), "--quiet"];
    for x in set {
        check.extend(["--set", x]);
        run.extend(["--set", x]);
    }
    let err = assert_clean_failure(&saltus(&check));
    assert!(err.contains(key), "{err}");
    assert_eq!(assert_clean_failure(&saltus(&run)), err, "check and run disagree");
    err
}

#[test]
fn a_derived_fluid_cell_count_beyond_its_range_is_refused_by_check_and_run() {
    // 6 mm grains under 1000 m of water: cells of d/30 would be 5e6, above the 1e6 that
    // solver.lagrangian.cells allows (the run took 9.4 GB, or aborted)
    let err = refused_alike("cells_derived", &fixture("deep_water_dem.toml"), &[], "solver.lagrangian.cells");
    assert!(err.contains("1000000") && err.contains("give it"), "{err}");
    // given within its range, the same column is accepted
    let o =
        saltus(&["check", fixture("deep_water_dem.toml").to_str().unwrap(), "--set", "solver.lagrangian.cells=1000"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn the_resolved_scene_of_an_eulerian_case_under_deep_water_checks_again() {
    // case 1 under 250 m of water: the DEM's default cells (1.25e6) are beyond their range;
    // the Eulerian scene is valid, and the resolved scene it prints must be too, with
    // the same text
    let d = tmp_dir("resolved_deep_water");
    let o = saltus(&["check", CASE01, "--set", "domain.water_depth=250"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let first = stdout(&o);
    let resolved = write(&d, "resolved.toml", &first);
    let again = saltus(&["check", resolved.to_str().unwrap()]);
    assert!(again.status.success(), "{}", stderr(&again));
    let body = |t: &str| t.lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&stdout(&again)), body(&first));
    assert!(!first.contains("\ncells = 1250"), "{first}");
}

#[test]
fn grains_passing_through_each_other_stop_the_run_naming_the_overlap_and_the_keys() {
    let out = tmp_dir("soft_contacts");
    let o = saltus(&["run", fixture("soft_contacts.toml").to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let (err, s) = assert_unstable(&o, &out);
    for want in ["overlap / d = ", "in particle ", "particles.contact.stiffness = 3.7", "solver.lagrangian.dt_safety"] {
        assert!(err.contains(want), "{want}: {err}");
    }
    let value: f64 = err.split("overlap / d = ").nth(1).and_then(|t| t.split(' ').next()).unwrap().parse().unwrap();
    assert!(value > saltus_solvers::lagrangian::MAX_OVERLAP && value < 1.0, "{value}");
    assert!(s["error"].as_str().is_some_and(|e| e.contains("overlap")), "{s}");
    let csv = std::fs::read_to_string(out.join("profiles.csv")).unwrap();
    assert!(!csv.to_lowercase().contains("nan") && !csv.contains("inf"), "{csv}");
}

#[test]
fn a_short_eulerian_run_is_diagnosed_whole() {
    // after 1 s the bed has one cell where every field of a comparison is defined: its
    // figure is drawn about that height and every comparison is written
    let out = tmp_dir("diagnose_short_eulerian");
    let o = saltus(&["run", CASE01, "--set", "solver.eulerian.end_time=1", "--out", out.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = saltus(&["diagnose", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let summary = std::fs::read_to_string(out.join("diagnose/summary.csv")).unwrap();
    let used: Vec<&str> = summary.lines().skip(1).filter(|l| l.split(',').nth(3).is_some_and(|n| n != "0")).collect();
    assert!(!used.is_empty(), "{summary}");
    for line in used {
        let c = line.split(',').collect::<Vec<_>>();
        let stem = saltus::compare::slug(&format!("{} {}", c[0], c[2]));
        assert_png(&out.join("diagnose").join(format!("{stem}.png")));
    }
}

#[test]
fn a_run_never_writes_over_its_scene_file_and_refuses_an_empty_folder() {
    let d = tmp_dir("scene_kept");
    let text = format!("# my notes\n{BASE}{RUNNABLE}[solver.eulerian]\nend_time = 0.01\n");
    let scene = write(&d, "scene.toml", &text);
    let s = scene.to_str().unwrap();
    let o = saltus(&["run", s, "--out", d.to_str().unwrap(), "-q"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("over the scene file") && err.contains("scene.toml"), "{err}");
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), text, "the scene file was changed");
    assert!(!d.join("profiles.csv").exists(), "the run went on");
    refused_alike("scene_kept_empty_dir", &scene, &["output.dir=\"\""], "output.dir");
    // the run's own resolved scene, run into its folder again, is rewritten with the
    // same text: nothing is lost, so that is allowed
    let out = d.join("out");
    assert!(saltus(&["run", s, "--out", out.to_str().unwrap(), "-q"]).status.success());
    let written = out.join("scene.toml");
    let before = std::fs::read_to_string(&written).unwrap();
    let o = saltus(&["run", written.to_str().unwrap(), "--out", out.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&written).unwrap(), before);
    // ... but not with another end time, which would change it
    let o = saltus(&[
        "run",
        written.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--set",
        "solver.eulerian.end_time=0.02",
        "-q",
    ]);
    assert!(assert_clean_failure(&o).contains("over the scene file"));
    assert_eq!(std::fs::read_to_string(&written).unwrap(), before);
}

#[test]
fn errors_name_the_key_inside_a_reference_and_cut_a_megabyte_key() {
    let o = check_scene("reference_columns", &format!("{RUNNABLE}[[reference]]\nfile = \"x.txt\"\ncolumns = 3\n"));
    let err = assert_clean_failure(&o);
    assert!(err.contains("key `reference[0].columns`") && err.contains("invalid type"), "{err}");
    let o = check_scene("reference_columns_one", &format!("{RUNNABLE}[reference]\nfile = \"x.txt\"\ncolumns = [1]\n"));
    assert!(assert_clean_failure(&o).contains("key `reference.columns[0]`"));
    let long = "k".repeat(1_000_000);
    for (name, extra) in [
        ("long_key_domain", format!("[domain]\n{long} = 1\n")),
        ("long_key_top", format!("{long} = 1\n")),
        ("long_model", format!("[closures.drag]\ntype = \"{long}\"\n")),
    ] {
        let err = assert_clean_failure(&check_scene(name, &extra));
        assert!(err.len() < 2000 && err.contains("(1000000 characters)"), "{name}: {} bytes", err.len());
    }
}

#[test]
fn the_paragraph_names_an_unnamed_scene_and_gives_a_short_time_in_full() {
    let d = tmp_dir("unnamed_short");
    let scene = write(&d, "unnamed.toml", &format!("{BASE}{RUNNABLE}[solver.eulerian]\nend_time = 3e-4\n"));
    let o = saltus(&["run", scene.to_str().unwrap(), "--out", d.join("out").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    // three steps of 1e-4 s
    assert!(out.starts_with("unnamed: end_time after 3.00000e-4 s simulated"), "{out}");
}

#[test]
fn a_restart_continues_in_the_folder_it_restarts_from() {
    let d = tmp_dir("restart_in_place");
    let dir = d.join("run");
    let o = dir.to_str().unwrap();
    let scene = fixture("small_dem_bed.toml");
    let s = scene.to_str().unwrap();
    let first = saltus(&["run", s, "--out", o, "-q"]);
    assert!(first.status.success(), "{}", stderr(&first));
    assert!(dir.join("checkpoint.bin").is_file());
    let rows = |p: &Path| std::fs::read_to_string(p.join("timeseries.csv")).unwrap().lines().count();
    let before = rows(&dir);
    // the default folder of the scene, where a continued run went before
    let default = Path::new(env!("CARGO_MANIFEST_DIR")).join("out/small_dem_bed_restart_probe");
    let _ = std::fs::remove_dir_all(&default);
    let more = saltus(&["run", s, "--restart", o, "--set", "solver.lagrangian.end_time=0.04", "-q"]);
    assert!(more.status.success(), "{}", stderr(&more));
    assert!(!default.exists(), "the continued run wrote into {}", default.display());
    let summary = summary(&dir);
    assert_eq!(summary["ending"].as_str(), Some("end_time"), "{summary}");
    // the DEM's time is a whole number of steps (of 2.6e-5 s here)
    assert!((summary["sim_time_s"].as_f64().unwrap() - 0.04).abs() < 1e-4, "{summary}");
    assert!(rows(&dir) > before, "the time series did not go on");
    // the folder's own scene restarts in place too (its text is rewritten unchanged)
    let own = dir.join("scene.toml");
    let again = saltus(&["run", own.to_str().unwrap(), "--restart", o, "-q"]);
    assert!(again.status.success(), "{}", stderr(&again));
}

/// `domain.initial_profiles` refused alike by `check` and `run`, naming the key: a file
/// that does not exist, one without `u_f`, profiles with sediment for a clear-fluid scene,
/// a DEM scene, and a two-equation turbulence closure whose k and omega no profile holds.
#[test]
fn initial_profiles_that_cannot_start_the_column_are_refused_alike() {
    let stokes = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/verification/stokes_layer.toml");
    let d = tmp_dir("initial_profiles_files");
    let no_uf = write(&d, "no_uf.csv", "z,u_p\n0,0.1\n0.001,0.2\n");
    let sediment = write(&d, "sediment.csv", "z,u_f,phi\n0,0.1,0.3\n0.001,0.2,0.3\n");
    let key = "domain.initial_profiles";
    let set = |p: &Path| format!("domain.initial_profiles=\"{}\"", p.display());
    let e = refused_alike("ip_missing", &stokes, &[&set(&d.join("nowhere.csv"))], key);
    assert!(e.contains("nowhere.csv"), "{e}");
    let e = refused_alike("ip_no_uf", &stokes, &[&set(&no_uf)], key);
    assert!(e.contains("u_f"), "{e}");
    let e = refused_alike("ip_sediment", &stokes, &[&set(&sediment)], key);
    assert!(e.contains("sediment"), "{e}");
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/chassagne2023/case01.toml");
    let good = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/verification/stokes_layer_t0.csv");
    refused_alike("ip_dem", &case, &["solver.type=lagrangian", &set(&good)], key);
    let e = refused_alike("ip_k_omega", &case, &["closures.turbulence={type=\"k_omega\"}", &set(&good)], key);
    assert!(e.contains("k and omega"), "{e}");
}
