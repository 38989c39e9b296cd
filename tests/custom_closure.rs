//! The out-of-tree example crate `examples/custom_closure` (a drag law of its own and a
//! 3-line binary running the saltus command line) builds, and its binary lists the model,
//! runs scenes with it in both solvers and refuses an unknown key of it.
//!
//! The example is built by a nested cargo into this build's own target folder, with this
//! build's profile and the workspace's lock file copied beside it, so that it reuses every
//! compiled dependency: only the example itself (and `saltus`, when changed) compiles.
//! Cargo holds its build lock only while it compiles, not while the tests run, so the
//! nested build does not wait on the outer one.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use common::{stderr, stdout, tmp_dir, write, CASE01};

/// Build the example once per test binary; its binary's path.
fn example_binary() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        // target/tmp -> target
        let target = Path::new(env!("CARGO_TARGET_TMPDIR")).parent().expect("target folder").to_path_buf();
        let (profile_flag, profile_dir) =
            if cfg!(debug_assertions) { (None, "debug") } else { (Some("--release"), "release") };
        let start = std::time::Instant::now();
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args(["build", "--offline", "--bin", "saltus-custom", "--manifest-path"])
            .arg(root.join("examples/custom_closure/Cargo.toml"))
            .env("CARGO_TARGET_DIR", &target)
            .current_dir(root);
        if let Some(f) = profile_flag {
            cmd.arg(f);
        }
        let o = cmd.output().expect("run cargo");
        assert!(o.status.success(), "building examples/custom_closure failed:\n{}", stderr(&o));
        eprintln!("examples/custom_closure built in {:.1} s", start.elapsed().as_secs_f64());
        target.join(profile_dir).join("saltus-custom")
    })
}

fn custom(args: &[&str]) -> Output {
    Command::new(example_binary())
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run saltus-custom")
}

#[test]
fn the_example_binary_lists_its_model_with_ours() {
    let o = custom(&["models", "drag"]);
    let out = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.contains("  cheng2009\n") && out.contains("Cheng 2009, Powder Technol. 189"), "{out}");
    assert!(out.contains("  dallavalle\n"), "ours are still there:\n{out}");
    assert!(out.contains("exponent b of the viscous correction"), "{out}");
}

#[test]
fn the_example_model_passes_closure_check() {
    let o = custom(&["closure", "check", "--family", "drag", "--model", "type = \"cheng2009\""]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    assert!(out.contains("limit stokes") && out.contains("all 6 checks passed"), "{out}");
}

#[test]
fn a_scene_with_the_example_model_runs_in_both_solvers() {
    let d = tmp_dir("custom_closure_runs");
    let eulerian = d.join("eulerian");
    let o = custom(&[
        "run",
        CASE01,
        "--set",
        "closures.drag={type=\"cheng2009\"}",
        "--set",
        "domain.cells=40",
        "--set",
        "solver.eulerian.end_time=5.0",
        "--out",
        eulerian.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "eulerian: {}", stderr(&o));
    let resolved = std::fs::read_to_string(eulerian.join("scene.toml")).unwrap();
    assert!(resolved.contains("type = \"cheng2009\""), "{resolved}");

    let lagrangian = d.join("lagrangian");
    let o = custom(&[
        "run",
        CASE01,
        "--set",
        "closures.drag={type=\"cheng2009\", c=0.5}",
        "--set",
        "solver.type=\"lagrangian\"",
        "--set",
        "solver.lagrangian.length=0.06",
        "--set",
        "solver.lagrangian.width=0.06",
        "--set",
        "domain.bed_height=0.036",
        "--set",
        "domain.water_depth=0.03",
        "--set",
        "domain.cells=60",
        "--set",
        "solver.lagrangian.settle_time=0.05",
        "--set",
        "solver.lagrangian.end_time=0.2",
        "--set",
        "solver.lagrangian.stats_start=0.0",
        "--out",
        lagrangian.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "lagrangian: {}", stderr(&o));
    let resolved = std::fs::read_to_string(lagrangian.join("scene.toml")).unwrap();
    assert!(resolved.contains("cheng2009") && resolved.contains("c = 0.5"), "{resolved}");
}

#[test]
fn an_unknown_key_of_the_example_model_is_refused_with_file_and_key() {
    let d = tmp_dir("custom_closure_unknown_key");
    let scene = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(CASE01)).unwrap();
    let p = write(&d, "scene.toml", &scene);
    let o = custom(&["check", p.to_str().unwrap(), "--set", "closures.drag={type=\"cheng2009\", cc=0.5}"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("scene.toml") && err.contains("closures.drag.cc"), "{err}");
    assert!(err.contains("a, b, c, k, m") || err.contains("`c`"), "names what is allowed: {err}");
}
