//! `physics.shields` with `physics.drive`, and `domain.cell_size`: the quantity each sets,
//! shown resolved by `check`, against the Shields number's definition; contradictions
//! and drives the flow cannot take refused naming the key.

mod common;

use common::*;

/// The resolved scene of `extra` (after [`BASE`]), as a TOML table.
fn resolved(name: &str, extra: &str) -> toml::Table {
    let o = check_scene(name, extra);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    text.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n").parse().unwrap()
}

fn float(t: &toml::Table, table: &str, key: &str) -> f64 {
    t[table][key].as_float().unwrap_or_else(|| panic!("{table}.{key}: {:?}", t[table].get(key)))
}

const GRANULAR: &str = "[closures.granular]\ntype = \"mu_i\"\n";

/// theta = rho_f g sin h_w / ((rho_p - rho_f) g cos d), the bed-normal weight by
/// default; the vertical weight drops the cos.
#[test]
fn the_shields_number_sets_the_water_depth_under_a_slope() {
    let t = resolved(
        "shields_depth",
        &format!("[physics]\nslope = 0.1\nshields = 0.3\ndrive = \"water_depth\"\n[domain]\nbed_height = 0.03\ncell_size = \"d/4\"\n{GRANULAR}"),
    );
    let (d, r) = (6e-3, 1.5);
    let cos = (1.0f64 - 0.01).sqrt();
    let h = float(&t, "domain", "water_depth");
    assert!((h - 0.3 * r * d * cos / 0.1).abs() < 1e-15, "{h}");
    let cells = t["domain"]["cells"].as_integer().unwrap();
    assert_eq!(cells, ((0.03 + h) / (d / 4.0)).round() as i64);
    let t = resolved(
        "shields_depth_vertical",
        &format!("[physics]\nslope = 0.1\nshields = 0.3\ndrive = \"water_depth\"\nshields_weight = \"vertical\"\n[domain]\ncells = 10\n{GRANULAR}"),
    );
    let h = float(&t, "domain", "water_depth");
    assert!((h - 0.3 * r * d / 0.1).abs() < 1e-15, "{h}");
}

/// The summary's nominal Shields number, computed by the solver from the resolved
/// depth, is the number the scene asked for.
#[test]
fn a_run_reports_the_shields_number_it_was_driven_at() {
    let d = tmp_dir("shields_run");
    let p = write(
        &d,
        "scene.toml",
        &format!("{BASE}[physics]\nslope = 0.05\nshields = 0.45\ndrive = \"water_depth\"\n[domain]\nbed_height = 0.03\ncell_size = 1.5e-3\n[solver.eulerian]\nend_time = 0.5\n{GRANULAR}"),
    );
    let out = d.join("out");
    let o = saltus(&["run", p.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let nominal = summary(&out)["shields_nominal"].as_f64().unwrap();
    assert!((nominal - 0.45).abs() < 1e-12, "{nominal}");
}

#[test]
fn the_shields_number_sets_a_slope_or_a_pressure_gradient() {
    let (d, r, h, g) = (6e-3, 1.5, 0.05, 9.81);
    let t = resolved(
        "shields_slope",
        &format!("[physics]\nshields = 0.5\ndrive = \"slope\"\n[domain]\nwater_depth = {h}\ncells = 10\n{GRANULAR}"),
    );
    let s = float(&t, "physics", "slope");
    // rho_f h tan(alpha) = theta (rho_p - rho_f) d
    let tan = s / (1.0 - s * s).sqrt();
    assert!((tan - 0.5 * r * d / h).abs() < 1e-14, "{s}");
    // Cheng et al.: u*^2 = G h / rho_f, theta = u*^2 / ((s - 1) g d)
    let t = resolved(
        "shields_gradient",
        &format!("[physics]\nshields = 0.5\ndrive = \"pressure_gradient\"\n[domain]\nwater_depth = {h}\ncells = 10\n{GRANULAR}"),
    );
    let grad = float(&t, "physics", "pressure_gradient");
    assert!((grad - 0.5 * 1500.0 * g * d / h).abs() < 1e-10, "{grad}");
    // the resolved scene reads again to the same numbers
    let d2 = tmp_dir("shields_again");
    let again = write(&d2, "again.toml", &toml::to_string(&t).unwrap());
    let o = saltus(&["check", again.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn contradictions_and_drives_the_flow_cannot_take_are_refused() {
    let cases: [(&str, &str, &[&str]); 10] = [
        ("given", "[physics]\nslope = 0.1\nshields = 0.3\ndrive = \"water_depth\"\n[domain]\nwater_depth = 0.1\ncells = 10\n", &["domain.water_depth", "physics.shields"]),
        ("no_drive", "[physics]\nslope = 0.1\nshields = 0.3\n[domain]\ncells = 10\n", &["physics.drive", "missing"]),
        ("no_shields", "[physics]\nslope = 0.1\ndrive = \"slope\"\n[domain]\nwater_depth = 0.1\ncells = 10\n", &["physics.shields", "missing"]),
        ("lid", "[physics]\nshields = 0.3\ndrive = \"pressure_gradient\"\n[domain]\nwater_depth = 0.1\ncells = 10\ntop = \"lid\"\n", &["physics.drive", "lid"]),
        ("no_push", "[physics]\nshields = 0.3\ndrive = \"water_depth\"\n[domain]\ncells = 10\n", &["physics.drive", "slope or a pressure gradient"]),
        ("steep", "[physics]\nshields = 50\ndrive = \"slope\"\nshields_weight = \"vertical\"\n[domain]\nwater_depth = 0.01\ncells = 10\n", &["physics.shields", "> 1"]),
        ("cells", "[domain]\nwater_depth = 0.1\ncell_size = \"d/4\"\ncells = 10\n", &["domain.cells", "cell_size"]),
        ("stretched", "[domain]\nwater_depth = 0.1\ncell_size = 1e-3\nstretching = 1.1\n", &["domain.cell_size", "stretching"]),
        ("size_text", "[domain]\nwater_depth = 0.1\ncell_size = \"quarter\"\n", &["domain.cell_size", "d/4"]),
        // a DEM scene whose size makes a million cells: refused by the column's own cap
        // (1e5, below the DEM's 1e6) before any run
        ("dem_cells", "[domain]\nwater_depth = 100.0\ncell_size = 1e-4\n[solver]\ntype = \"lagrangian\"\n", &["domain.cell_size", "100000 cells"]),
    ];
    for (name, extra, words) in cases {
        let o = check_scene(&format!("shields_bad_{name}"), &format!("{extra}{GRANULAR}"));
        let err = assert_clean_failure(&o);
        assert!(err.contains("scene.toml"), "{name}: {err}");
        for w in words {
            assert!(err.contains(w), "{name}: `{w}` not in {err}");
        }
    }
}
