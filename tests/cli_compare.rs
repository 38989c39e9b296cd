//! `saltus compare` through the command line: one scene under several variants (closures,
//! solvers), global overrides, bad compare files and failing variants.

mod common;

use std::path::{Path, PathBuf};

use common::*;

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
    // the summary columns of the table are those the library names, in its order; the
    // ones scripts read by name are there
    for c in ["qs_star", "shields", "flux_layer_thickness", "steady", "mass_error"] {
        assert!(saltus::compare::COLUMNS.contains(&c), "{c}");
    }
    let mut expected = vec!["variant"];
    expected.extend(saltus::compare::COLUMNS);
    if dem {
        expected.extend(["rms_phi", "rms_u_p", "rms_u_f", "rms_theta_g"]);
        expected.extend(["bed_shift", "aligned_rms_phi", "aligned_rms_u_f", "surface_u_f"]);
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
fn the_precision_table_of_a_grid_study_shows_second_order_convergence() {
    // case 1 in the two-fluid model at 30, 60, 120 and 240 cells against 960: phi on a
    // uniform grid converges at second order (docs/performance.md), so its RMS error falls
    // by close to 4 per doubling; the reference has no error; a deterministic run has a
    // zero statistical bar; each run's CPU time is measured
    let d = tmp_dir("compare_precision");
    let mut text = String::from("[reference]\nvariant = \"960\"\n");
    for n in [30, 60, 120, 240, 960] {
        text.push_str(&format!("[[variant]]\nname = \"{n}\"\nset = ['domain.cells={n}']\n"));
    }
    let p = compare_file(&d, &text);
    let out = d.join("out");
    let o = saltus(&["compare", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = read_table(&out.join("precision.csv"));
    assert_eq!(
        header[..7],
        ["variant", "cpu_time_s", "wall_time_s", "qs_star", "qs_star_stderr", "qs_star_error", "qs_star_error_bar"]
    );
    let num = |r: usize, c: &str| -> f64 { cell(&header, &rows[r], c).parse().unwrap() };
    assert_eq!(rows.len(), 5);
    for r in 0..5 {
        assert!(num(r, "cpu_time_s") > 0.0 && num(r, "qs_star_error_bar") == 0.0, "{rows:?}");
        assert!(cell(&header, &rows[r], "qs_star_stderr").is_empty());
    }
    assert_eq!((num(4, "qs_star_error"), num(4, "rms_phi")), (0.0, 0.0));
    for r in 0..3 {
        let ratio = num(r, "rms_phi") / num(r + 1, "rms_phi");
        assert!(ratio > 2.2, "RMS phi {} -> {}: ratio {ratio}", num(r, "rms_phi"), num(r + 1, "rms_phi"));
    }
    // qs* within 2 % of the finest run from 30 cells on, and 0.1 % at 240
    assert!(num(0, "qs_star_error").abs() < 0.02 && num(3, "qs_star_error").abs() < 1e-3, "{rows:?}");
    assert_png(&out.join("precision.png"));
    assert!(stdout(&o).contains("work against precision"), "{}", stdout(&o));
}

#[test]
fn a_bad_reference_is_refused_naming_the_key() {
    let d = tmp_dir("compare_bad_reference");
    let out = d.join("out");
    let run = |p: &Path| saltus(&["compare", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let cases = [
        ("[reference]\nvariant = \"b\"\n", "reference.variant"),
        ("[reference]\n", "reference"),
        ("[reference]\nvariant = \"a\"\ndata = true\n", "reference"),
        ("[reference]\nqs_star = nan\n", "reference.qs_star"),
        ("[reference]\nqs_star = -1.0\n", "reference.qs_star"),
        ("[reference]\ndata = true\nqs_star_stderr = 0.1\n", "reference.qs_star_stderr"),
        ("[reference]\nvariants = \"a\"\n", "variants"),
        ("[reference]\nvariant = \"a\"\nsmooth = nan\n", "reference.smooth"),
        ("[reference]\nvariant = \"a\"\nsmooth = 0.0\n", "reference.smooth"),
        ("[reference]\nvariant = \"a\"\nsmooth = 1e308\n", "reference.smooth"),
        ("[reference]\nvariant = \"a\"\nsmooth = \"one\"\n", "smooth"),
        ("[reference]\ndata = true\nsmooth = 1.0\n", "reference.smooth"),
        ("[reference]\nqs_star = 2.0\nalign = true\n", "reference.align"),
    ];
    for (text, key) in cases {
        let p = compare_file(&d, &format!("{text}[[variant]]\nname = \"a\"\n"));
        let err = assert_clean_failure(&run(&p));
        assert!(err.contains("cmp.toml") && err.contains(key), "{text}: {err}");
    }
    assert!(!out.join("comparison.csv").exists(), "nothing runs on a bad reference");
}
