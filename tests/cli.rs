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
    let ok =
        check_scene("met", "[closures.turbulence]\ntype = \"mixing_length\"\n[closures.fluctuation]\ntype = \"drw\"\n");
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
    let d = tmp_dir("no_solver_run");
    let p = write(&d, "scene.toml", BASE);
    let err = assert_clean_failure(&saltus(&["run", p.to_str().unwrap()]));
    assert!(err.contains("solver.type"), "{err}");
    let p = write(&d, "lagrangian.toml", &format!("{BASE}[solver]\ntype = \"lagrangian\"\n"));
    let err = assert_clean_failure(&saltus(&["run", p.to_str().unwrap()]));
    assert!(err.contains("domain") && err.contains("Lagrangian"), "{err}");
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
        "solver.max_phi_change=1e-6",
        "--set",
        "solver.dt_initial=0.1",
        "--set",
        "solver.dt_min=0.01",
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
        "physics.pressure_gradient=1e10",
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
fn compare_runs_both_models_of_case01() {
    let d = tmp_dir("compare_case01");
    let o = saltus(&["compare", COMPARE01, "--out", d.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = read_table(&d.join("comparison.csv"));
    // the DEM profile of the base scene's [reference] lives outside the repository
    // (../shared/data); without it the table has no rms_ columns
    let dem = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data/chassagne_dem_bedload_sedfoam/BedloadTurbDEM.txt")
        .is_file();
    let mut expected = vec![
        "variant",
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
    let p = write(&d, "scene.toml", &format!("{BASE}{extra}"));
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
            "cases/chassagne2023/dem_case01.toml",
            "--set",
            "domain.length=0.06",
            "--set",
            "domain.width=0.06",
            "--set",
            "domain.bed_height=0.036",
            "--set",
            "domain.water_depth=0.03",
            "--set",
            "domain.cells=120",
            "--set",
            "solver.settle_time=0.05",
            "--set",
            "solver.end_time=1000.0",
            "--set",
            "solver.stats_start=0.0",
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
