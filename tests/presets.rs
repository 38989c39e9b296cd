//! `accuracy = "draft" | "standard" | "fine"`: each preset resolves to the numbers
//! documented in docs/scenes.md, `"standard"` leaves every shipped scene as it resolves
//! without a preset, keys given in the scene win over the preset, a bad name is refused
//! naming the file, the key and the names allowed, and `run` uses what `check` prints.

mod common;

use std::path::Path;

use common::*;
use saltus_core::scene::{Accuracy, Scene};

/// A column of 27.5 d (d = 6 mm): default cells 110 (d/4), DEM fluid cells 825 (d/30).
/// The granular closure an Eulerian scene needs, then `[domain]` (open for more keys).
const COLUMN: &str = "[closures.granular]\ntype = \"mu_i\"\n[domain]\nbed_height = 0.06\nwater_depth = 0.105\n";

fn load(dir: &str, text: &str, set: &[&str]) -> Scene {
    saltus_closures::link();
    let d = tmp_dir(dir);
    let p = write(&d, "scene.toml", &format!("{BASE}{text}"));
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Scene::from_file_with(&p, &set).unwrap_or_else(|e| panic!("{e}"))
}

/// (preset, Eulerian cells, steady tolerance, dt_safety, DEM fluid cells, DEM end time,
/// stats_start), as the table of docs/scenes.md gives them.
const DOCUMENTED: [(&str, usize, f64, f64, usize, f64, f64); 3] = [
    ("draft", 55, 1e-4, 0.22, 275, 10.0, 0.0),
    ("standard", 110, 1e-6, 0.05, 825, 10.0, 0.0),
    ("fine", 220, 1e-6, 0.05, 825, 20.0, 10.0),
];

#[test]
fn presets_resolve_to_the_documented_values() {
    for (name, cells, tol, dt, fluid_cells, end, start) in DOCUMENTED {
        let s = load("presets_documented", COLUMN, &[&format!("accuracy={name}")]);
        assert_eq!(s.accuracy.map(Accuracy::name), Some(name));
        assert_eq!(s.domain.cells, Some(cells), "{name}");
        assert_eq!(s.solver.eulerian.steady_tolerance, tol, "{name}");
        let l = &s.solver.lagrangian;
        assert_eq!((l.dt_safety, l.cells, l.end_time, l.stats_start), (dt, Some(fluid_cells), end, start), "{name}");
    }
    // without a preset: the standard numbers, and nothing written for it
    let s = load("presets_documented", COLUMN, &[]);
    assert_eq!(s.accuracy, None);
    assert_eq!(s.domain.cells, Some(110));
    assert!(!s.to_toml().unwrap().contains("accuracy"));
}

#[test]
fn standard_leaves_every_shipped_scene_as_it_was() {
    saltus_closures::link();
    let mut scenes = 0;
    let mut dirs = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("cases")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                dirs.push(p);
                continue;
            }
            if p.extension().is_none_or(|e| e != "toml") {
                continue;
            }
            // compare, sweep and closures files, and scenes that need a Python host, are not
            // scenes this test can load
            let Ok(plain) = Scene::from_file(&p) else { continue };
            let mut standard = Scene::from_file_with(&p, &["accuracy=standard".to_string()])
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert_eq!(standard.accuracy, Some(Accuracy::Standard), "{}", p.display());
            standard.accuracy = None;
            assert_eq!(plain.to_toml().unwrap(), standard.to_toml().unwrap(), "{}", p.display());
            scenes += 1;
        }
    }
    assert!(scenes >= 50, "only {scenes} shipped scenes loaded");
}

#[test]
fn keys_given_in_the_scene_win_over_the_preset() {
    let given = format!(
        "{COLUMN}cells = 77\n[solver.eulerian]\nsteady_tolerance = 1e-5\n\
         [solver.lagrangian]\ndt_safety = 0.1\ncells = 300\nend_time = 15.0\n"
    );
    for name in ["draft", "fine"] {
        let s = load("presets_given", &given, &[&format!("accuracy={name}")]);
        assert_eq!(s.domain.cells, Some(77), "{name}");
        assert_eq!(s.solver.eulerian.steady_tolerance, 1e-5, "{name}");
        let l = &s.solver.lagrangian;
        assert_eq!((l.dt_safety, l.cells, l.end_time), (0.1, Some(300), 15.0), "{name}");
    }
    // the fine window starts at half the end time the scene gives, unless it gives a start
    let s = load("presets_given", &given, &["accuracy=fine"]);
    assert_eq!(s.solver.lagrangian.stats_start, 7.5);
    let s = load("presets_given", &given, &["accuracy=fine", "solver.lagrangian.stats_start=3"]);
    assert_eq!(s.solver.lagrangian.stats_start, 3.0);
    // --set wins as the file's keys do
    let s = load("presets_given", COLUMN, &["accuracy=draft", "solver.lagrangian.dt_safety=0.05", "domain.cells=90"]);
    assert_eq!((s.solver.lagrangian.dt_safety, s.domain.cells), (0.05, Some(90)));
    // a cell size sets both counts
    let s = load("presets_given", &format!("{COLUMN}cell_size = \"d/4\"\n"), &["accuracy=draft"]);
    assert_eq!(s.solver.lagrangian.cells, Some(275));
    let s =
        load("presets_given", &format!("{COLUMN}cell_size = \"d/4\"\n"), &["accuracy=draft", "solver.type=lagrangian"]);
    assert_eq!((s.domain.cells, s.solver.lagrangian.cells), (Some(110), Some(110)));
    assert_eq!(s.domain.cells, Some(110));
    // the resolved scene holds every number: resolved again with its preset, the same
    let text = load("presets_given", COLUMN, &["accuracy=fine"]).to_toml().unwrap();
    let d = tmp_dir("presets_given_again");
    let p = write(&d, "resolved.toml", &text);
    assert_eq!(Scene::from_file(&p).unwrap().to_toml().unwrap(), text);
}

#[test]
fn a_bad_preset_is_refused_naming_the_file_the_key_and_the_names() {
    let d = tmp_dir("presets_bad");
    for (k, bad) in ["accuracy=\"coarse\"", "accuracy=3"].iter().enumerate() {
        let err = assert_clean_failure(&saltus(&["check", CASE01, "--set", bad]));
        assert!(err.contains("case01.toml") && err.contains("`accuracy`"), "{err}");
        assert!(err.contains("\"draft\", \"standard\", \"fine\""), "{err}");
        let out = d.join(format!("run{k}"));
        let run = assert_clean_failure(&saltus(&["run", CASE01, "--set", bad, "--out", out.to_str().unwrap()]));
        assert!(run.contains("`accuracy`"), "{run}");
        assert!(!out.exists(), "run --set {bad} started work before refusing");
    }
}

#[test]
fn check_prints_the_preset_and_run_uses_what_check_prints() {
    let d = tmp_dir("presets_check_run");
    let p = write(&d, "scene.toml", &format!("{BASE}{COLUMN}[solver.eulerian]\nend_time = 0.2\n"));
    let scene = p.to_str().unwrap();
    let check = saltus(&["check", scene, "--set", "accuracy=draft"]);
    assert!(check.status.success(), "{}", stderr(&check));
    let printed: toml::Table = stdout(&check).parse().unwrap();
    assert_eq!(printed["accuracy"].as_str(), Some("draft"));
    assert_eq!(printed["domain"]["cells"].as_integer(), Some(55));
    assert_eq!(printed["solver"]["lagrangian"]["dt_safety"].as_float(), Some(0.22));
    let out = d.join("run");
    let run = saltus(&["run", scene, "--set", "accuracy=draft", "--out", out.to_str().unwrap(), "-q"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let written: toml::Table = std::fs::read_to_string(out.join("scene.toml")).unwrap().parse().unwrap();
    for key in ["accuracy", "domain", "solver", "particles", "closures"] {
        assert_eq!(written[key], printed[key], "{key}");
    }
    assert_eq!(summary(&out)["solver"].as_str(), Some("eulerian"));
}
