//! The scene through the command line: `check` and `run` refuse the same inputs, errors
//! name the full key path, grains are stated once, one case switches solver, and the
//! written scene reproduces its run.

mod common;

use std::path::Path;
use std::process::Command;

use common::*;

#[test]
fn run_refuses_bad_scenes_cleanly() {
    let err = assert_clean_failure(&saltus(&["run", "does/not/exist.toml"]));
    assert!(err.contains("does/not/exist.toml"), "{err}");
    // no [solver]: the documented default, the Eulerian solver, which needs a column
    let d = tmp_dir("no_solver_run");
    let p = write(&d, "scene.toml", BASE);
    let err = assert_clean_failure(&saltus(&["run", p.to_str().unwrap()]));
    assert!(err.contains("domain.water_depth"), "{err}");
    let p = write(&d, "lagrangian.toml", &format!("{BASE}[solver]\ntype = \"lagrangian\"\n"));
    let err = assert_clean_failure(&saltus(&["run", p.to_str().unwrap()]));
    assert!(err.contains("domain.bed_height") && err.contains("initial = \"bed\""), "{err}");
}

/// Bad inputs refused by `check` and by `run` alike, before any work (no output folder),
/// each naming the key: (override, key named).
const BAD_INPUTS: [(&str, &str); 18] = [
    ("solver.dt_maxx=1", "solver.dt_maxx"),
    ("solver.eulerian.dt_maxx=1", "solver.eulerian.dt_maxx"),
    ("solver.eulerian.dt_max=nan", "solver.eulerian.dt_max"),
    ("solver.type=\"implicit\"", "solver.type"),
    ("domain.cells=1000000000", "domain.cells"),
    ("domain.water_depth=1e308", "domain.water_depth"),
    ("domain.bed_phi=0.7", "domain.bed_phi"),
    ("particles.restitution=1.5", "particles.restitution"),
    ("particles.diameter=1e-308", "particles.diameter"),
    ("particles=[1,2]", "particles"),
    ("meta=[]", "meta"),
    ("solver.lagrangian=[1]", "solver.lagrangian"),
    ("solver.lagrangian.length=1e308", "solver.lagrangian.length"),
    ("particles.contact.law=\"sticky\"", "particles.contact.law"),
    ("closures.granular.g0={type=\"chialvo_sundaresan\", a00=1}", "closures.granular.g0.a00"),
    ("closures.turbulence.form=\"nope\"", "closures.turbulence.form"),
    ("solver.lagrangian.phi_diffusion=1e308", "solver.lagrangian.phi_diffusion"),
    ("closures.fluctuation={type=\"eim\", drag_reynolds=\"median\"}", "closures.fluctuation.drag_reynolds"),
];

#[test]
fn check_refuses_exactly_what_run_refuses() {
    let d = tmp_dir("check_equals_run");
    for (k, (set, key)) in BAD_INPUTS.iter().enumerate() {
        let check = assert_clean_failure(&saltus(&["check", CASE01, "--set", set]));
        assert!(check.contains(key) && check.contains("case01.toml"), "check --set {set}: {check}");
        let out = d.join(format!("run{k}"));
        let run = assert_clean_failure(&saltus(&["run", CASE01, "--set", set, "--out", out.to_str().unwrap()]));
        assert!(run.contains(key), "run --set {set}: {run}");
        assert!(!out.exists(), "run --set {set} started work before refusing");
    }
    // refused only when the solver is set up (the gas lattice does not fit in the box):
    // `check` and `run` go through the same set-up
    let gas = "cases/verification/dem_homogeneous_cooling.toml";
    let set = "solver.lagrangian.particles=50000";
    let check = assert_clean_failure(&saltus(&["check", gas, "--set", set]));
    let out = d.join("run_gas");
    let run = assert_clean_failure(&saltus(&["run", gas, "--set", set, "--out", out.to_str().unwrap()]));
    for e in [&check, &run] {
        assert!(e.contains("solver.lagrangian.particles") && e.contains("do not fit"), "{e}");
    }
    assert!(!out.exists(), "run started work before refusing");
    // the same bad DEM inputs whichever solver is active: both tables are always checked
    for (set, key) in [
        ("solver.lagrangian.dt_safety=0.9", "solver.lagrangian.dt_safety"),
        ("solver.eulerian.eddy_relaxation=0", "solver.eulerian.eddy_relaxation"),
        ("solver.eulerian.target_field_change=0", "solver.eulerian.target_field_change"),
        ("solver.eulerian.target_field_change=nan", "solver.eulerian.target_field_change"),
        ("solver.eulerian.target_field_change=1e308", "solver.eulerian.target_field_change"),
        ("solver.lagrangian.phi_diffusion=nan", "solver.lagrangian.phi_diffusion"),
        ("solver.lagrangian.phi_diffusion=1e308", "solver.lagrangian.phi_diffusion"),
        ("solver.lagrangian.phi_diffusion=-1", "solver.lagrangian.phi_diffusion"),
        ("solver.lagrangian.phi_average=\"weekly\"", "solver.lagrangian.phi_average"),
        ("closures.fluctuation={type=\"eim\", drag_reynolds=\"median\"}", "closures.fluctuation.drag_reynolds"),
    ] {
        for kind in ["eulerian", "lagrangian"] {
            let t = format!("solver.type={kind}");
            let check = assert_clean_failure(&saltus(&["check", CASE01, "--set", &t, "--set", set]));
            assert!(check.contains(key), "{kind} --set {set}: {check}");
        }
    }
    // a DEM box over 1e7 particles is refused at load, not at allocation
    let err = assert_clean_failure(&saltus(&[
        "check",
        CASE01,
        "--set",
        "solver.type=lagrangian",
        "--set",
        "solver.lagrangian.length=50",
        "--set",
        "solver.lagrangian.width=50",
    ]));
    assert!(err.contains("solver.lagrangian.length") && err.contains("particles"), "{err}");
}

#[test]
fn closure_errors_name_the_full_key_path() {
    for (set, key) in [
        ("closures.granular.g0={type=\"chialvo_sundaresan\", a00=1}", "closures.granular.g0.a00"),
        ("closures.granular.g0={type=\"chialvo_sundaresan\", a0=\"x\"}", "closures.granular.g0.a0"),
        ("closures.granular.saltation.c0=\"x\"", "closures.granular.saltation.c0"),
        ("closures.granular.phi_rlp=1.5", "closures.granular.phi_rlp"),
        ("closures.turbulence.form=\"nope\"", "closures.turbulence.form"),
        ("closures.granular.saltation=[true]", "closures.granular.saltation"),
    ] {
        let err = assert_clean_failure(&saltus(&["check", CASE01, "--set", set]));
        assert!(err.contains(&format!("`{key}`")), "--set {set}: {err}");
    }
}

#[test]
fn grains_are_stated_once_and_the_kinetic_closure_inherits_or_overrides_them() {
    let resolved = |sets: &[&str]| {
        let mut args = vec!["check", CASE01];
        for s in sets {
            args.extend(["--set", s]);
        }
        let o = saltus(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = stdout(&o);
        let t: toml::Table =
            text.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n").parse().unwrap();
        t
    };
    let t = resolved(&["particles.restitution=0.9"]);
    assert_eq!(t["closures"]["granular"]["restitution"].as_float(), Some(0.9));
    assert_eq!(t["closures"]["granular"]["friction"].as_float(), Some(0.4));
    let t = resolved(&["particles.restitution=0.9", "closures.granular.restitution=0.5"]);
    assert_eq!(t["closures"]["granular"]["restitution"].as_float(), Some(0.5));
    assert_eq!(t["particles"]["restitution"].as_float(), Some(0.9));
}

#[test]
fn case01_switched_to_the_dem_resolves_the_derived_defaults() {
    let o = saltus(&["check", CASE01, "--set", "solver.type=lagrangian"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let t: toml::Table = text.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n").parse().unwrap();
    let d = 6e-3;
    let lag = &t["solver"]["lagrangian"];
    assert_eq!(t["solver"]["type"].as_str(), Some("lagrangian"));
    // a 20 d x 20 d cell, fluid cells of d/30 over bed + water (30.5 d)
    assert!((lag["length"].as_float().unwrap() - 20.0 * d).abs() < 1e-15);
    assert!((lag["width"].as_float().unwrap() - 20.0 * d).abs() < 1e-15);
    assert_eq!(lag["cells"].as_integer(), Some(915));
    // the rigid limit gives the validated stiffness of the paper's DEM
    assert_eq!(t["particles"]["contact"]["stiffness"].as_float(), Some(1.0e4));
    assert_eq!(t["domain"]["bed_phi"].as_float(), Some(0.6));
    // the settle time a scene leaves out: three free falls of the released lattice under
    // the buoyant weight, (bed + 3 d) 0.6 / (pi / 6 / 1.1^3) high
    let o = saltus(&["check", CASE01, "--set", "solver.type=lagrangian", "--set", "solver.lagrangian={}"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let t: toml::Table =
        stdout(&o).lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n").parse().unwrap();
    let release = (0.075 + 3.0 * d) * 0.6 / (saltus_core::grain::sphere_volume(1.0) / 1.331);
    let expected = 3.0 * (2.0 * release / (9.81 * (1.0 - 1000.0 / 2500.0))).sqrt();
    let settle = t["solver"]["lagrangian"]["settle_time"].as_float().unwrap();
    assert!((settle - expected).abs() <= 5e-4, "{settle} vs {expected}");
}

#[test]
fn the_written_scene_reproduces_the_run_byte_for_byte_from_another_folder() {
    let d = tmp_dir("scene_reproduces");
    let first = d.join("first");
    let o = saltus(&[
        "run",
        CASE01,
        "--set",
        "domain.cells=40",
        "--set",
        "solver.eulerian.end_time=0.5",
        "--out",
        first.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let elsewhere = d.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::copy(first.join("scene.toml"), elsewhere.join("copied.toml")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(["run", "copied.toml", "--out", "second"])
        .current_dir(&elsewhere)
        .output()
        .expect("run saltus");
    assert!(o.status.success(), "{}", stderr(&o));
    let a = std::fs::read(first.join("profiles.csv")).unwrap();
    let b = std::fs::read(elsewhere.join("second/profiles.csv")).unwrap();
    assert!(a == b, "profiles.csv differs between the run and the run of its scene.toml");
    // the resolved scene holds the numerics used, the reference path absolute
    let text = std::fs::read_to_string(first.join("scene.toml")).unwrap();
    for key in ["dt_max = ", "eddy_relaxation = ", "elastic_p0 = ", "[solver.lagrangian]", "stiffness = "] {
        assert!(text.contains(key), "scene.toml lacks {key}");
    }
    let t: toml::Table = text.parse().unwrap();
    let file = t["reference"][0]["file"].as_str().unwrap();
    assert!(Path::new(file).is_absolute(), "{file}");
}
