//! Integration tests of the `saltus` program: listing, scene checking, bad input, closure
//! evaluation and plots. Every bad input must give exit code 2 with a message naming the
//! file, the key and what is allowed, never a panic.

mod common;

use common::*;

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
    let o = closure_eval(
        "hindrance",
        "{type = \"richardson_zaki\", exponent = 2.0}",
        &write(&d, "h.csv", "phi,re_p\n0.5,1\n"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    let last: f64 = s.lines().nth(1).unwrap().split(',').nth(2).unwrap().parse().unwrap();
    assert!((last - 4.0).abs() < 1e-12, "{s}");
}

/// The wall friction: the laminar plane-Poiseuille wall (f Re = 48) below Re = 618, the
/// undefined f of a laminar law at rest as an empty cell, a frictionless wall 0 everywhere,
/// and a negative Re refused naming its column.
#[test]
fn closure_eval_wall_friction() {
    let d = tmp_dir("eval_wall");
    let input = write(&d, "re.csv", "re\n0\n100\n");
    let o = closure_eval("wall_friction", "type = \"graf_altinakar\"", &input);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o).trim(), "re,f,f_re\n0,,48\n100,0.48,48");
    let o = closure_eval("wall_friction", "type = \"none\"", &input);
    assert_eq!(stdout(&o).trim(), "re,f,f_re\n0,0,0\n100,0,0");
    let o = closure_eval("wall_friction", "type = \"graf_altinakar\"", &write(&d, "neg.csv", "re\n-1\n"));
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("neg.csv: row 2: re = -1"), "{}", stderr(&o));
}

#[test]
fn closure_eval_kinetic_theory_and_granular() {
    let d = tmp_dir("eval_kt");
    let input = write(&d, "phi.csv", "phi\n0.01\n0.3\n0.55\n");
    let o = closure_eval("kinetic_theory", "restitution = 0.7", &input);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("phi,g0,f1,f2,f3,f4,e_eff"), "{}", stdout(&o));
    let input = write(&d, "i.csv", "i\n0\n0.69\n");
    let o = closure_eval("granular", "type = \"mu_i\"", &input);
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
    let err = assert_clean_failure(&closure_eval("drag", "type = \"stokes\"", &input));
    assert!(err.contains("re_p"), "{err}");
    let err = assert_clean_failure(&closure_eval("drag", "type = \"stoke\"", &input));
    assert!(err.contains("known") && err.contains("stokes"), "{err}");
    let bad = write(&d, "bad.csv", "re_p\nabc\n");
    let err = assert_clean_failure(&closure_eval("drag", "type = \"stokes\"", &bad));
    assert!(err.contains("bad.csv") && err.contains("abc"), "{err}");
    let err =
        assert_clean_failure(&closure_eval("viscosity", "type = \"einstein\"", &write(&d, "p.csv", "phi\n1.5\n")));
    assert!(err.contains("phi"), "{err}");
    let err = assert_clean_failure(&closure_eval("drag", "type = = 1", &input));
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

/// A closure figure whose sweep would not end or not fit in memory is refused by name:
/// too many points, a log range of more than 200 decades (whose axis's key points are
/// counted from the ratio of its ends), a linear range whose span overflows; a linear
/// range up to 1e308 draws.
#[test]
fn closure_plot_refuses_sweeps_beyond_its_limits() {
    let d = tmp_dir("plot_limits");
    let figure = |range: &str, points: &str, log: bool| {
        format!(
            "[[figure]]\nname = \"f\"\nfamily = \"drag\"\nx = \"re_p\"\ny = \"cd\"\nrange = {range}\npoints = {points}\nlog_x = {log}\nlog_y = {log}\n[[figure.model]]\nlabel = \"Stokes\"\nmodel = {{ type = \"stokes\" }}\n"
        )
    };
    for (name, range, points, log) in [
        ("many", "[0.01, 100.0]", "1000000000000", true),
        ("decades", "[1e-300, 1e300]", "10", true),
        ("one", "[0.01, 100.0]", "1", false),
        ("span", "[-1e308, 1e308]", "5", false),
    ] {
        let file = d.join(format!("{name}.toml"));
        std::fs::write(&file, figure(range, points, log)).unwrap();
        let o = saltus(&["closure", "plot", file.to_str().unwrap(), "--out", d.to_str().unwrap()]);
        let e = stderr(&o);
        assert!(!o.status.success() && e.contains("figure[0]") && e.contains("100000"), "{name}: {e}");
    }
    let file = d.join("wide.toml");
    std::fs::write(&file, figure("[0.0, 1e308]", "5", false)).unwrap();
    let o = saltus(&["closure", "plot", file.to_str().unwrap(), "--out", d.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("f.png").is_file());
}
