//! Regression tests of the findings of the scene fuzzer (`examples/fuzz_scenes.rs`): each minimal scene, run
//! through the built program, fails cleanly (exit 2 naming the key), stops as unstable
//! with its cause (exit 3), or runs, and never panics, aborts or writes a non-finite
//! number. Plus the ParaView series of a small DEM run, read back.

mod common;

use common::*;
use std::path::Path;

/// A small deposited DEM bed: 86 particles, 0.1 s of deposition and 0.1 s of flow.
const BED: &str = r#"seed = 1
[particles]
diameter = 6.0e-3
density = 2500.0
restitution = 0.5
friction = 0.4
[particles.contact]
stiffness = 5.0e3
[physics]
slope = 0.1
[domain]
water_depth = 0.03
bed_height = 0.012
[solver]
type = "lagrangian"
[solver.lagrangian]
length = 0.03
width = 0.03
initial = "bed"
cells = 20
fluid_period = 1.0e-2
settle_time = 0.1
end_time = 0.1
[closures.drag]
type = "dallavalle"
[closures.hindrance]
type = "richardson_zaki"
[closures.viscosity]
type = "clear_fluid"
[closures.turbulence]
type = "mixing_length"
"#;

/// Two listed particles in a wide dry box without gravity.
const LIST: &str = r#"seed = 1
[particles]
diameter = 6.0e-3
density = 2500.0
[particles.contact]
stiffness = 1.0e4
[physics]
gravity = 0.0
[domain]
water_depth = 0.05
[solver]
type = "lagrangian"
[solver.lagrangian]
length = 0.1
width = 0.1
bottom = "none"
initial = "list"
cells = 10
fluid = "off"
end_time = 0.002
fluid_period = 1.0e-3
[[solver.lagrangian.particle]]
position = [0.04, 0.05, 0.01]
[[solver.lagrangian.particle]]
position = [0.06, 0.05, 0.01]
"#;

fn scene(name: &str, text: &str) -> (std::path::PathBuf, String) {
    let d = tmp_dir(name);
    let p = write(&d, "scene.toml", text);
    (d, p.to_str().unwrap().to_string())
}

fn run_with(name: &str, text: &str, set: &[&str]) -> (std::process::Output, std::path::PathBuf) {
    let (d, p) = scene(name, text);
    let out = d.join("out");
    let mut args = vec!["run", p.as_str(), "--out", out.to_str().unwrap()];
    for s in set {
        args.extend(["--set", s]);
    }
    (saltus(&args), out)
}

/// `check` and `run` refuse alike, naming `key`.
fn refused(name: &str, text: &str, set: &[&str], key: &str) -> String {
    let (d, p) = scene(name, text);
    let mut check = vec!["check", p.as_str()];
    for s in set {
        check.extend(["--set", s]);
    }
    let err = assert_clean_failure(&saltus(&check));
    assert!(err.contains(key), "{err}");
    let (o, _) = run_with(name, text, set);
    assert_eq!(assert_clean_failure(&o), err, "check and run disagree");
    let _ = d;
    err
}

/// No `NaN` or `inf` in the outputs of a run.
fn finite_outputs(out: &Path) {
    for f in ["profiles.csv", "summary.json"] {
        let t = std::fs::read_to_string(out.join(f)).unwrap();
        let lower = t.to_lowercase();
        // serde_json writes a non-finite f64 as null
        assert!(!lower.contains("nan") && !lower.contains("inf") && !lower.contains("null"), "{f}: {t}");
    }
}

#[test]
fn a_fluid_period_beyond_the_run_stops_on_the_runaway_column_naming_it() {
    // was: index out of bounds in drag.rs
    let (o, out) = run_with("robust_fluid_period", BED, &["solver.lagrangian.fluid_period=1e6"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("u_f") && err.contains("solver.lagrangian.fluid_period = 1e6 s"), "{err}");
    assert!(!err.contains("panicked"));
    finite_outputs(&out);
}

#[test]
fn a_column_thinner_than_a_grain_is_refused() {
    // was: index out of bounds in drag.rs, then a singular column at t = 0
    let mut text = LIST.replace("fluid = \"off\"", "fluid = \"coupled\"");
    text = text.replace("gravity = 0.0", "gravity = 9.81");
    refused("robust_water_depth", &text, &["domain.water_depth=1e-308"], "domain.water_depth");
}

#[test]
fn extreme_grain_and_box_sizes_are_refused_with_readable_bounds() {
    // were: a panic in neighbours.rs and a capacity overflow
    refused("robust_diameter", LIST, &["particles.diameter=1e-308"], "particles.diameter");
    let err = refused("robust_length", LIST, &["solver.lagrangian.length=1e308"], "solver.lagrangian.length");
    assert!(err.contains("= 1e308: out of range, allowed (0.0132, 60]"), "{err}");
}

#[test]
fn two_grains_far_apart_in_a_wide_box_do_not_exhaust_memory() {
    // was: an abort asking for 6.9e14 bytes of neighbour cells
    let (o, out) = run_with(
        "robust_wide_box",
        LIST,
        &[
            "solver.lagrangian.length=60",
            "solver.lagrangian.width=60",
            "solver.lagrangian.particle=[{position=[1,1,0.01]},{position=[1,1,1e6]}]",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    finite_outputs(&out);
}

#[test]
fn a_time_step_that_underflows_is_refused_before_the_run() {
    // was: a deposition that never ended
    let err = refused("robust_dt", BED, &["solver.lagrangian.dt_safety=1e-308"], "solver.lagrangian.dt_safety");
    assert!(err.contains("particles.contact.stiffness") && err.contains("more than 1e15"), "{err}");
    let hertz =
        ["particles.contact.law=\"hertz\"", "particles.contact.young=1e12", "solver.lagrangian.dt_safety=1e-300"];
    let err = refused("robust_dt_hertz", BED, &hertz, "solver.lagrangian.dt_safety");
    assert!(err.contains("particles.contact.young"), "{err}");
}

#[test]
fn a_full_stderr_does_not_panic() {
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full");
    let Ok(full) = full else { return };
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(["check", CASE01, "--set", "closures.drag={type=\"nope\"}"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn an_os_error_is_told_once() {
    let o = saltus(&["check", "no/such/scene.toml"]);
    let err = assert_clean_failure(&o);
    assert_eq!(err.matches("os error 2").count(), 1, "{err}");
}

#[test]
fn the_couette_lid_column_runs_at_any_cell_count() {
    // was: "singular momentum system" from 133 cells on (a 0/0 in the drag tangent)
    let d = tmp_dir("robust_couette");
    let out = d.join("out");
    let o = saltus(&[
        "run",
        "cases/verification/couette_laminar.toml",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "domain.cells=400",
        "--set",
        "solver.eulerian.end_time=0.5",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    finite_outputs(&out);
}

#[test]
fn a_stretched_grid_spanning_more_than_four_decades_is_refused() {
    // was: a first cell of 3.9e-34 m and theta_g < 0 at the first step
    let (_, p) = scene("robust_stretch", &std::fs::read_to_string(CASE01).unwrap());
    let o = saltus(&["check", &p, "--set", "domain.stretching=1.2", "--set", "domain.cells=400"]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("domain.stretching") && err.contains("at most 51 cells"), "{err}");
    assert!(saltus(&["check", &p, "--set", "domain.stretching=1.2", "--set", "domain.cells=51"]).status.success());
}

#[test]
fn elastic_phi_rlp_follows_a_low_packing() {
    // was: the default 0.57 refused for any mu(I) with phi_c <= 0.57
    let o = check_scene("robust_rlp", &format!("{RUNNABLE}phi_c = 0.55\n"));
    let out = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    let want = 0.55 * 0.57 / 0.61;
    let line = out.lines().find(|l| l.starts_with("elastic_phi_rlp")).expect("resolved elastic_phi_rlp");
    let got: f64 = line.split('=').nth(1).unwrap().trim().parse().unwrap();
    assert!((got - want).abs() < 1e-12, "{line}");
}

#[test]
fn an_eulerian_run_writes_no_non_finite_number() {
    // was: inertial_number = inf in every particle-free cell; qs* = NaN with s = 1
    let d = tmp_dir("robust_eulerian");
    for (k, set) in [("a", "particles.density=2650"), ("b", "particles.density=1000"), ("c", "physics.gravity=0")] {
        let out = d.join(k);
        let o = saltus(&[
            "run",
            CASE01,
            "--out",
            out.to_str().unwrap(),
            "--set",
            set,
            "--set",
            "domain.cells=40",
            "--set",
            "solver.eulerian.end_time=0.2",
        ]);
        assert!(o.status.code() == Some(0) || o.status.code() == Some(3), "{}", stderr(&o));
        finite_outputs(&out);
        let (header, rows) = read_table(&out.join("profiles.csv"));
        for r in &rows {
            let phi: f64 = cell(&header, r, "phi").parse().unwrap();
            assert!(phi >= 0.0);
        }
    }
}

#[test]
fn a_dem_run_writes_a_paraview_series_that_reads_back() {
    let (o, out) = run_with("robust_vtk", BED, &["solver.lagrangian.vtk_period=0.02"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let vtk = out.join("vtk");
    let pvd = std::fs::read_to_string(vtk.join("series.pvd")).unwrap();
    let entries: Vec<(f64, u32, String)> = pvd
        .lines()
        .filter(|l| l.starts_with("<DataSet"))
        .map(|l| {
            let attr = |a: &str| l.split(&format!("{a}=\"")).nth(1).unwrap().split('"').next().unwrap().to_string();
            (attr("timestep").parse().unwrap(), attr("part").parse().unwrap(), attr("file"))
        })
        .collect();
    // the flow lasts 0.1 s: snapshots of the state at the ends of the fluid periods at or
    // after 0, 0.02, ... 0.1 s (the flow's first state and its last included), each at the
    // time of the state it holds
    let times: Vec<f64> = entries.iter().filter(|e| e.1 == 0).map(|e| e.0).collect();
    assert_eq!(times.len(), 6, "{pvd}");
    assert_eq!(times[0], 0.0);
    for (k, t) in times.iter().enumerate() {
        assert!(*t >= 0.02 * k as f64 - 1e-12 && *t < 0.02 * k as f64 + 0.011, "{times:?}");
    }
    assert_eq!(entries.iter().filter(|e| e.1 == 1).count(), 6, "a column per snapshot");
    // the last particle snapshot holds the particles of the run, at finite positions
    let last = &entries.iter().rfind(|e| e.1 == 0).unwrap().2;
    let text = std::fs::read_to_string(vtk.join(last)).unwrap();
    let points = read_array(&text, "Points");
    let n = summary(&out)["particles"].as_u64().unwrap() as usize;
    let fixed = read_u8(&text, "fixed");
    assert_eq!(fixed.iter().filter(|&&f| f == 0).count(), n);
    assert_eq!(points.len(), 3 * fixed.len());
    assert!(points.iter().all(|v| v.is_finite()));
    // positions are wrapped into the periodic box at the neighbour-list builds only
    assert!(points.chunks(3).all(|p| p[0] > -6e-3 && p[0] < 0.036 && p[2] >= 0.0 && p[2] < 0.05));
    let column = entries.iter().rfind(|e| e.1 == 1).unwrap();
    let text = std::fs::read_to_string(vtk.join(&column.2)).unwrap();
    let u = read_array(&text, "u_f");
    assert_eq!(u.len() as u64, summary(&out)["cells"].as_u64().unwrap(), "one point per cell of the column");
    assert!(u.iter().all(|v| v.is_finite()) && u.iter().any(|&v| v > 0.0));
}

/// The bytes of the binary (base64, UInt64 header) array `name` of a `.vtp` document.
fn read_bytes(text: &str, name: &str) -> Vec<u8> {
    let tail = text.split(&format!("Name=\"{name}\"")).nth(1).unwrap_or_else(|| panic!("no array {name}"));
    assert!(tail[..tail.find('>').unwrap()].contains("format=\"binary\""));
    let data = &tail[tail.find('>').unwrap() + 1..tail.find('<').unwrap()];
    const B64: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let vals: Vec<u32> =
        data.bytes().filter(|&c| c != b'=').map(|c| B64.iter().position(|&b| b == c).unwrap() as u32).collect();
    let mut out = Vec::new();
    for c in vals.chunks(4) {
        let v = c.iter().enumerate().fold(0u32, |a, (k, &b)| a | (b << (18 - 6 * k)));
        out.extend(&v.to_be_bytes()[1..c.len()]);
    }
    let len = u64::from_le_bytes(out[..8].try_into().unwrap()) as usize;
    assert_eq!(len, out.len() - 8);
    out.split_off(8)
}

fn read_array(text: &str, name: &str) -> Vec<f64> {
    read_bytes(text, name).chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}

fn read_u8(text: &str, name: &str) -> Vec<u8> {
    read_bytes(text, name)
}

#[test]
fn an_unknown_drag_velocity_is_refused_naming_the_allowed_ones() {
    let set = ["solver.lagrangian.drag_velocity=\"middle\""];
    let err = refused("robust_drag_velocity", BED, &set, "solver.lagrangian.drag_velocity");
    assert!(err.contains("scene.toml") && err.contains("`centre`") && err.contains("`sphere_average`"), "{err}");
}

#[test]
fn a_size_dispersion_is_refused_beyond_the_lattice_or_without_a_deposited_bed() {
    let key = "solver.lagrangian.size_dispersion";
    refused("robust_dispersion_range", BED, &["solver.lagrangian.size_dispersion=0.2"], key);
    let err = refused("robust_dispersion_list", LIST, &["solver.lagrangian.size_dispersion=0.05"], key);
    assert!(err.contains("initial = \"bed\""), "{err}");
}
