//! Integration tests of the `saltus` program: listing, scene checking, bad input, closure
//! evaluation and plots. Every bad input must give exit code 2 with a message naming the
//! file, the key and what is allowed, never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn saltus(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run saltus")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A failure that is clean: exit code 2, a line starting with `error:` on stderr (after
/// any warnings, e.g. reference data missing from a checkout without ../shared), no panic.
fn assert_clean_failure(o: &Output) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "expected exit 2, got {:?}: {err}", o.status);
    assert!(err.lines().any(|l| l.starts_with("error:")), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

fn tmp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const BASE: &str = "[particles]\ndiameter = 6e-3\ndensity = 2500.0\n";
/// What a scene without `[solver]` (the Eulerian by default) needs beyond [`BASE`] to pass
/// `check`, which refuses what `run` would.
const RUNNABLE: &str = "[domain]\nwater_depth = 0.1\ncells = 10\n[closures.granular]\ntype = \"mu_i\"\n";

fn check_scene(name: &str, extra: &str) -> Output {
    let d = tmp_dir(name);
    let p = write(&d, "scene.toml", &format!("{BASE}{extra}"));
    saltus(&["check", p.to_str().unwrap()])
}

#[test]
fn models_lists_every_family_with_parameters_and_sources() {
    let o = saltus(&["models"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for family in ["drag", "hindrance", "viscosity", "granular", "turbulence", "fluctuation"] {
        assert!(text.contains(&format!("[closures.{family}]")), "missing family {family}");
    }
    for model in [
        "stokes",
        "dallavalle",
        "schiller_naumann",
        "haider_levenspiel",
        "richardson_zaki",
        "di_felice",
        "clear_fluid",
        "einstein",
        "batchelor_green",
        "krieger_dougherty",
        "gibilaro",
        "fry2024",
        "mu_i",
        "mu_k",
        "frictional_collisional",
        "laminar",
        "mixing_length",
        "drw",
        "eim",
    ] {
        assert!(text.contains(&format!("\n  {model}\n")), "model {model} not listed");
    }
    assert!(text.contains("cd_inf") && text.contains("Chassagne"), "parameters or sources missing");
    let one = stdout(&saltus(&["models", "drag"]));
    assert!(one.contains("[closures.drag]") && !one.contains("[closures.granular]"));
    let bad = saltus(&["models", "dragg"]);
    let err = assert_clean_failure(&bad);
    assert!(err.contains("known: drag, hindrance"), "{err}");
}

#[test]
fn models_json_is_parseable_and_names_are_unique_per_family() {
    let o = saltus(&["models", "--json"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let arr = v.as_array().unwrap();
    assert!(arr.len() >= 19, "only {} models registered", arr.len());
    let mut seen = std::collections::HashSet::new();
    for m in arr {
        let key = (m["family"].as_str().unwrap().to_string(), m["name"].as_str().unwrap().to_string());
        assert!(seen.insert(key.clone()), "duplicate model {key:?}");
    }
}

#[test]
fn check_fills_defaults_and_prints_the_resolved_scene() {
    let o = saltus(&["check", "cases/chassagne2023/case01.toml"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    // resolved text parses as TOML and carries defaults that the file did not state
    let body: String = text.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n");
    let t: toml::Table = body.parse().unwrap();
    assert_eq!(t["closures"]["drag"]["cd_inf"].as_float(), Some(0.4));
    assert_eq!(t["closures"]["fluctuation"]["type"].as_str(), Some("none"));
    assert_eq!(t["fluid"]["density"].as_float(), Some(1000.0));
}

#[test]
fn check_applies_set_overrides() {
    let o = saltus(&[
        "check",
        "cases/chassagne2023/case01.toml",
        "--set",
        "closures.drag={type=\"stokes\"}",
        "--set",
        "physics.slope=0.02",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("type = \"stokes\""), "{text}");
    assert!(text.contains("slope = 0.02"), "{text}");
}

#[test]
fn unknown_model_lists_known_ones() {
    let o = check_scene("unknown_model", "[closures.drag]\ntype = \"dalavalle\"\n");
    let err = assert_clean_failure(&o);
    assert!(err.contains("closures.drag.type"), "{err}");
    assert!(err.contains("dalavalle") && err.contains("dallavalle") && err.contains("stokes"), "{err}");
}

#[test]
fn unknown_fields_are_rejected_with_their_path() {
    let err =
        assert_clean_failure(&check_scene("unknown_field", "[closures.drag]\ntype = \"dallavalle\"\ncdinf = 0.4\n"));
    assert!(err.contains("closures.drag") && err.contains("cdinf"), "{err}");
    let err = assert_clean_failure(&check_scene("unknown_top", "[fluid]\ndensity = 1000.0\nviscosty = 1e-6\n"));
    assert!(err.contains("viscosty"), "{err}");
    let err = assert_clean_failure(&check_scene("unknown_family", "[closures.dragg]\ntype = \"stokes\"\n"));
    assert!(err.contains("closures.dragg") && err.contains("known: drag"), "{err}");
}

#[test]
fn out_of_range_parameters_name_key_and_range() {
    let cases = [
        ("sphericity", "[closures.drag]\ntype = \"haider_levenspiel\"\nsphericity = 1.5\n", "closures.drag.sphericity"),
        (
            "sphericity0",
            "[closures.drag]\ntype = \"haider_levenspiel\"\nsphericity = 0.0\n",
            "closures.drag.sphericity",
        ),
        ("neg_visc", "[fluid]\nviscosity = -1e-6\n", "fluid.viscosity"),
        ("phi_m", "[closures.viscosity]\ntype = \"krieger_dougherty\"\nphi_m = 1.0\n", "closures.viscosity.phi_m"),
        (
            "e_high",
            "[closures.granular]\ntype = \"frictional_collisional\"\nrestitution = 1.2\n",
            "closures.granular.restitution",
        ),
        (
            "e_zero",
            "[closures.granular]\ntype = \"frictional_collisional\"\nrestitution = 0.0\n",
            "closures.granular.restitution",
        ),
        (
            "phi_max",
            "[closures.granular]\ntype = \"frictional_collisional\"\nphi_max = 1.0\n",
            "closures.granular.phi_max",
        ),
        ("diameter", "", "particles.diameter"),
    ];
    for (name, extra, key) in cases {
        let o = if name == "diameter" {
            let d = tmp_dir(name);
            let p = write(&d, "s.toml", "[particles]\ndiameter = -1.0\ndensity = 2500.0\n");
            saltus(&["check", p.to_str().unwrap()])
        } else {
            check_scene(name, extra)
        };
        let err = assert_clean_failure(&o);
        assert!(err.contains(key), "{name}: {err}");
        assert!(err.contains("allowed") || err.contains("range"), "{name}: {err}");
        assert!(err.contains("scene.toml") || err.contains("s.toml"), "{name}: file not named: {err}");
    }
}

#[test]
fn syntax_errors_show_line_and_column() {
    let err = assert_clean_failure(&check_scene("syntax", "[physics]\nslope = = 0.05\n"));
    assert!(err.contains("scene.toml:5:"), "{err}");
}

#[test]
fn missing_particles_and_wrong_types_are_clean_errors() {
    let d = tmp_dir("missing");
    let p = write(&d, "scene.toml", "[fluid]\ndensity = 1000.0\n");
    let err = assert_clean_failure(&saltus(&["check", p.to_str().unwrap()]));
    assert!(err.contains("particles"), "{err}");
    let err = assert_clean_failure(&check_scene("wrongtype", "[physics]\nslope = \"steep\"\n"));
    assert!(err.contains("physics.slope"), "{err}");
    let err = assert_clean_failure(&saltus(&["check", "does/not/exist.toml"]));
    assert!(err.contains("does/not/exist.toml"), "{err}");
}

#[test]
fn unmet_closure_need_names_both_models() {
    let err = assert_clean_failure(&check_scene(
        "unmet",
        "[closures.turbulence]\ntype = \"mixing_length\"\n[closures.fluctuation]\ntype = \"eim\"\n",
    ));
    assert!(err.contains("eim") && err.contains("mixing_length"), "{err}");
    let err = assert_clean_failure(&check_scene("unmet_laminar", "[closures.fluctuation]\ntype = \"drw\"\n"));
    assert!(err.contains("drw") && err.contains("laminar"), "{err}");
    // DRW is satisfied by a mixing length (Reynolds stress)
    let ok = check_scene(
        "met",
        &format!("{RUNNABLE}[closures.turbulence]\ntype = \"mixing_length\"\n[closures.fluctuation]\ntype = \"drw\"\n"),
    );
    assert!(ok.status.success(), "{}", stderr(&ok));
}

#[test]
fn closure_eval_writes_inputs_then_outputs() {
    let d = tmp_dir("eval");
    let input = write(&d, "in.csv", "re_p\n0.1\n1\n1000\n");
    let out = d.join("out.csv");
    let o = saltus(&[
        "closure",
        "eval",
        "--family",
        "drag",
        "--model",
        "type = \"dallavalle\"",
        "--input",
        input.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("re_p,cd"));
    let row: Vec<f64> = lines.next().unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    assert!((row[1] - (0.4 + 24.4 / 0.1)).abs() < 1e-9);
    // stdout without --output, inline-table model
    let o = saltus(&[
        "closure",
        "eval",
        "--family",
        "hindrance",
        "--model",
        "{type = \"richardson_zaki\", exponent = 2.0}",
        "--input",
        write(&d, "h.csv", "phi,re_p\n0.5,1\n").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    let last: f64 = s.lines().nth(1).unwrap().split(',').nth(2).unwrap().parse().unwrap();
    assert!((last - 4.0).abs() < 1e-12, "{s}");
}

#[test]
fn closure_eval_kinetic_theory_and_granular() {
    let d = tmp_dir("eval_kt");
    let input = write(&d, "phi.csv", "phi\n0.01\n0.3\n0.55\n");
    let o = saltus(&[
        "closure",
        "eval",
        "--family",
        "kinetic_theory",
        "--model",
        "restitution = 0.7",
        "--input",
        input.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("phi,g0,f1,f2,f3,f4,e_eff"), "{}", stdout(&o));
    let input = write(&d, "i.csv", "i\n0\n0.69\n");
    let o = saltus(&[
        "closure",
        "eval",
        "--family",
        "granular",
        "--model",
        "type = \"mu_i\"",
        "--input",
        input.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: Vec<Vec<f64>> =
        stdout(&o).lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    assert!((rows[0][1] - 0.35).abs() < 1e-12, "mu(0) = mu_s");
    assert!((rows[1][1] - 0.5 * (0.35 + 0.97)).abs() < 1e-12, "mu(I0) = (mu_s + mu_2)/2");
}

#[test]
fn closure_eval_bad_input_is_clean() {
    let d = tmp_dir("eval_bad");
    let input = write(&d, "in.csv", "phi\n0.1\n");
    let err = assert_clean_failure(&saltus(&[
        "closure",
        "eval",
        "--family",
        "drag",
        "--model",
        "type = \"stokes\"",
        "--input",
        input.to_str().unwrap(),
    ]));
    assert!(err.contains("re_p"), "{err}");
    let err = assert_clean_failure(&saltus(&[
        "closure",
        "eval",
        "--family",
        "drag",
        "--model",
        "type = \"stoke\"",
        "--input",
        input.to_str().unwrap(),
    ]));
    assert!(err.contains("known") && err.contains("stokes"), "{err}");
    let bad = write(&d, "bad.csv", "re_p\nabc\n");
    let err = assert_clean_failure(&saltus(&[
        "closure",
        "eval",
        "--family",
        "drag",
        "--model",
        "type = \"stokes\"",
        "--input",
        bad.to_str().unwrap(),
    ]));
    assert!(err.contains("bad.csv") && err.contains("abc"), "{err}");
    let err = assert_clean_failure(&saltus(&[
        "closure",
        "eval",
        "--family",
        "viscosity",
        "--model",
        "type = \"einstein\"",
        "--input",
        write(&d, "p.csv", "phi\n1.5\n").to_str().unwrap(),
    ]));
    assert!(err.contains("phi"), "{err}");
    let err = assert_clean_failure(&saltus(&[
        "closure",
        "eval",
        "--family",
        "drag",
        "--model",
        "type = = 1",
        "--input",
        input.to_str().unwrap(),
    ]));
    assert!(err.contains("syntax"), "{err}");
}

#[test]
fn closure_eval_help_lists_families_inputs_outputs() {
    let o = saltus(&["closure", "eval", "--help"]);
    let text = stdout(&o);
    for s in ["kinetic_theory", "re_p -> cd", "phi, re_p -> factor", "phi -> nu_ratio", "g0, f1, f2, f3, f4, e_eff"] {
        assert!(text.contains(s), "help lacks {s}:\n{text}");
    }
}

#[test]
fn closure_plot_writes_png_and_csv_for_every_figure() {
    let d = tmp_dir("plot");
    for file in ["cases/closures/drag.toml", "cases/closures/granular.toml"] {
        let o = saltus(&["closure", "plot", file, "--out", d.to_str().unwrap()]);
        assert!(o.status.success(), "{file}: {}", stderr(&o));
    }
    for stem in ["drag_cd", "hindrance", "viscosity", "kt_g0", "kt_f4", "mu_i", "mu_k"] {
        let png = std::fs::read(d.join(format!("{stem}.png"))).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{stem}.png is not a PNG");
        let csv = std::fs::read_to_string(d.join(format!("{stem}.csv"))).unwrap();
        assert!(csv.lines().count() > 100, "{stem}.csv too short");
    }
}

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
const BAD_INPUTS: [(&str, &str); 16] = [
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
    // the same bad DEM inputs whichever solver is active: both tables are always checked
    for (set, key) in [
        ("solver.lagrangian.dt_safety=0.9", "solver.lagrangian.dt_safety"),
        ("solver.eulerian.eddy_relaxation=0", "solver.eulerian.eddy_relaxation"),
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
    let release = (0.075 + 3.0 * d) * 0.6 / (std::f64::consts::PI / 6.0 / 1.331);
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

const CASE01: &str = "cases/chassagne2023/case01.toml";
const COMPARE01: &str = "cases/chassagne2023/compare_case01_models.toml";

fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{} is not a PNG", path.display());
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

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
    // exit 1: the run stopped, unstable, with its last good state written and reported
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "expected exit 1, got {:?}: {err}", o.status);
    assert!(!err.contains("panicked"), "{err}");
    let stop = err.lines().find(|l| l.starts_with("error:")).unwrap_or_else(|| panic!("{err}"));
    // the breakdown: time, cell, field, and where the outputs are
    assert!(
        stop.contains("unstable at t = ") && stop.contains(" in cell ") && stop.contains(d.to_str().unwrap()),
        "{stop}"
    );
    let s = summary(&d);
    assert_eq!(s["ending"].as_str(), Some("unstable"));
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
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "expected exit 1, got {:?}: {err}", o.status);
    assert!(err.contains("unstable at t = ") && err.contains("|v|") && err.contains("in particle 0"), "{err}");
    let s = summary(&d);
    assert_eq!(s["ending"].as_str(), Some("unstable"));
    // a fluid at rest has no averaging sample before the first fluid update: no invented
    // transport figures, and nothing non-finite
    for f in ["profiles.csv", "summary.json", "scene.toml", "manifest.json"] {
        assert!(d.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(d.join("profiles.csv")).unwrap();
    assert!(!csv.contains("NaN") && !csv.contains("inf"), "{csv}");
}

/// Rows of a CSV as (header, records).
fn read_table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let header = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r.records().map(|x| x.unwrap().iter().map(str::to_string).collect()).collect();
    (header, rows)
}

fn cell<'a>(header: &[String], row: &'a [String], name: &str) -> &'a str {
    &row[header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"))]
}

#[test]
fn compare_runs_case01_in_both_solvers_with_global_overrides() {
    // a short DEM (0.05 s deposition, 0.02 s of flow) and a short Eulerian run: the
    // command line's --set reaches every variant, the table says which solver ran
    let d = tmp_dir("compare_solvers");
    let o = saltus(&[
        "compare",
        "cases/chassagne2023/compare_case01_solvers.toml",
        "--set",
        "solver.lagrangian.settle_time=0.05",
        "--set",
        "solver.lagrangian.end_time=0.02",
        "--set",
        "solver.lagrangian.stats_start=0.0",
        "--set",
        "solver.eulerian.end_time=1.0",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = read_table(&d.join("comparison.csv"));
    assert_eq!(rows.len(), 2, "{rows:?}");
    assert_eq!(cell(&header, &rows[0], "solver"), "eulerian");
    assert_eq!(cell(&header, &rows[1], "solver"), "lagrangian");
    for r in &rows {
        assert!(cell(&header, r, "error").is_empty(), "{r:?}");
        for c in ["qs_star", "shields", "wall_time_s"] {
            assert!(cell(&header, r, c).parse::<f64>().is_ok_and(f64::is_finite), "{c}: {r:?}");
        }
    }
    let sim = |r: usize| cell(&header, &rows[r], "sim_time_s").parse::<f64>().unwrap();
    assert!((sim(0) - 1.0).abs() < 1e-9 && sim(1) <= 0.02 + 1e-3, "{rows:?}");
    assert_png(&d.join("comparison.png"));
    // an override of a key that does not exist is refused for the whole comparison
    let err = assert_clean_failure(&saltus(&[
        "compare",
        "cases/chassagne2023/compare_case01_solvers.toml",
        "--set",
        "solver.lagrangian.end_tim=1",
    ]));
    assert!(err.contains("solver.lagrangian.end_tim"), "{err}");
}

#[test]
fn compare_runs_both_models_of_case01() {
    let d = tmp_dir("compare_case01");
    let o = saltus(&["compare", COMPARE01, "--out", d.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = read_table(&d.join("comparison.csv"));
    // the DEM profile of the base scene's [reference] lives outside the repository
    // (../shared/data); without it the table has no rms_ columns
    let dem_file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/chassagne_dem_bedload_sedfoam/BedloadTurbDEM.txt");
    let dem = dem_file.is_file();
    if !dem {
        saltus_core::data::missing(&dem_file, "the rms columns against the DEM profile");
    }
    let mut expected = vec![
        "variant",
        "solver",
        "qs_star",
        "qs",
        "shields",
        "bed_height",
        "transport_layer_thickness",
        "steady",
        "sim_time_s",
        "steps",
        "wall_time_s",
        "mass_error",
    ];
    if dem {
        expected.extend(["rms_phi", "rms_u_p", "rms_u_f", "rms_theta_g"]);
    }
    expected.push("error");
    assert_eq!(header, expected);
    assert_eq!(rows.len(), 2, "{rows:?}");
    if dem {
        // against the DEM profile the proposed model is closer in phi and u_p, as in the
        // paper's figures 3 and 8
        let rms = |r: usize, c: &str| -> f64 { cell(&header, &rows[r], c).parse().unwrap() };
        assert!(rms(1, "rms_phi") < rms(0, "rms_phi") && rms(1, "rms_u_p") < rms(0, "rms_u_p"), "{rows:?}");
    }
    assert_eq!(cell(&header, &rows[0], "variant"), "initial (Garzo-Dufty)");
    assert_eq!(cell(&header, &rows[1], "variant"), "proposed");
    let qs: Vec<f64> = rows.iter().map(|r| cell(&header, r, "qs_star").parse().unwrap()).collect();
    assert!(qs.iter().all(|q| q.is_finite() && *q > 0.0), "{qs:?}");
    assert!((qs[0] - qs[1]).abs() > 1e-3 * qs[1], "the two models give the same qs*: {qs:?}");
    assert!(rows.iter().all(|r| cell(&header, r, "error").is_empty()), "{rows:?}");
    assert_png(&d.join("comparison.png"));
    for v in ["initial-garzo-dufty", "proposed"] {
        assert!(d.join(v).join("summary.json").is_file(), "{v}/summary.json missing");
        assert_png(&d.join(v).join("profiles.png"));
    }
    // the proposed variant is case01 as it stands
    let scene = std::fs::read_to_string(d.join("proposed/scene.toml")).unwrap();
    assert!(scene.contains("jenkins_zhang"), "{scene}");
    let out = stdout(&o);
    assert!(out.contains("qs_star") && out.contains("initial (Garzo-Dufty)") && out.contains("proposed"), "{out}");
}

fn compare_file(dir: &Path, text: &str) -> PathBuf {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join(CASE01);
    write(dir, "cmp.toml", &format!("base = '{}'\n{text}", base.display()))
}

#[test]
fn bad_compare_files_are_refused_naming_file_and_key() {
    let d = tmp_dir("compare_bad");
    let out = d.join("out");
    let run = |p: &Path| saltus(&["compare", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let p = compare_file(&d, "[[variant]]\nname = \"a\"\nsett = []\n");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("cmp.toml") && err.contains("sett"), "{err}");
    let p = compare_file(&d, "[meta]\nname = \"x\"\ntitle = \"y\"\n[[variant]]\nname = \"a\"\n");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("cmp.toml") && err.contains("meta") && err.contains("title"), "{err}");
    let p = write(&d, "cmp.toml", "base = 'nowhere.toml'\n[[variant]]\nname = \"a\"\n");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("cmp.toml") && err.contains("`base`") && err.contains("nowhere.toml"), "{err}");
    let p = compare_file(&d, "[[variant]]\nname = = \"a\"\n");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("cmp.toml:3:"), "{err}");
    let p = compare_file(&d, "");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("variant"), "{err}");
    let p = compare_file(&d, "[[variant]]\nname = \"a b\"\n[[variant]]\nname = \"a-b\"\n");
    let err = assert_clean_failure(&run(&p));
    assert!(err.contains("variant[1].name"), "{err}");
    assert!(!out.join("comparison.csv").exists(), "nothing runs on a bad compare file");
}

#[test]
fn compare_reports_a_failing_variant_and_runs_the_others() {
    let d = tmp_dir("compare_failing");
    let p = compare_file(
        &d,
        "[[variant]]\nname = \"bad drag\"\nset = ['closures.drag={type=\"stoke\"}']\n\
         [[variant]]\nname = \"coarse\"\nset = ['domain.cells=60']\n",
    );
    let out = d.join("out");
    let o = saltus(&["compare", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let err = assert_clean_failure(&o);
    assert!(err.contains("1 of 2 variants failed"), "{err}");
    let (header, rows) = read_table(&out.join("comparison.csv"));
    assert_eq!(rows.len(), 2);
    let e = cell(&header, &rows[0], "error");
    assert!(e.contains("closures.drag.type") && e.contains("stoke"), "{e}");
    assert!(cell(&header, &rows[0], "qs_star").is_empty());
    assert!(cell(&header, &rows[1], "error").is_empty(), "{rows:?}");
    assert!(cell(&header, &rows[1], "qs_star").parse::<f64>().unwrap() > 0.0);
    assert_png(&out.join("comparison.png"));
    assert!(stdout(&o).contains("bad drag"), "{}", stdout(&o));
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
fn ctrl_c_stops_a_run_with_its_outputs_written_and_exit_130() {
    // a small DEM bed with a long flow: interrupted in the middle, it writes the state of
    // that time and says so
    let d = tmp_dir("run_interrupted");
    let mut child = Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args([
            "run",
            "cases/chassagne2023/case01.toml",
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
            "domain.cells=120",
            "--set",
            "solver.lagrangian.settle_time=0.05",
            "--set",
            "solver.lagrangian.end_time=1000.0",
            "--set",
            "solver.lagrangian.stats_start=0.0",
            "--out",
            d.to_str().unwrap(),
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run saltus");
    std::thread::sleep(std::time::Duration::from_secs(3));
    let pid = child.id().to_string();
    let sent = Command::new("kill").args(["-INT", &pid]).status().expect("kill");
    assert!(sent.success());
    let start = std::time::Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > std::time::Duration::from_secs(120) {
            let _ = child.kill();
            panic!("the run did not stop within 120 s of Ctrl-C");
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let o = child.wait_with_output().expect("output");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted at t = ") && err.contains(d.to_str().unwrap()), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let s = summary(&d);
    assert_eq!(s["ending"].as_str(), Some("interrupted"));
    assert!(d.join("profiles.csv").is_file() && d.join("scene.toml").is_file());
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
