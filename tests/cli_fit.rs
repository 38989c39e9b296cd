//! `saltus diagnose --fit` and `saltus run --closures`: closures fitted on a DEM run, run
//! in the Eulerian solver and held against the DEM; a closures file with an unknown family
//! or key refused by `run` and `check` alike, naming the file and the key.

mod common;

use std::path::Path;

use common::*;

const INCLINE: &str = "cases/granular/dry_incline.toml";
/// Grain diameter of the dry incline (m).
const D: f64 = 6e-3;
/// The Eulerian column of the dry incline: air (the DEM's is dry; rho_f / rho_p = 5e-4 is
/// the buoyancy's share), and the DEM's grain inventory (12 d at phi 0.6) spread at phi =
/// 0.55, near the flowing layer's, so that the layer starts near its own height.
const EULERIAN: [&str; 5] = [
    "solver.type=eulerian",
    "fluid.density=1.2",
    "fluid.viscosity=1.5e-5",
    "domain.bed_phi=0.55",
    "domain.bed_height=0.07854545454545454",
];

/// (z, phi, inertial number) of a run's profiles.
fn columns(dir: &Path) -> Vec<(f64, f64, f64)> {
    let (h, rows) = read_table(&dir.join("profiles.csv"));
    let num = |r: &[String], c: &str| cell(&h, r, c).parse::<f64>().unwrap_or(f64::NAN);
    rows.iter().map(|r| (num(r, "z"), num(r, "phi"), num(r, "inertial_number"))).collect()
}

/// Mean of the finite values.
fn mean(v: Vec<f64>) -> f64 {
    let v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// The loop on a short dry incline at 25 degrees (5 d x 5 d, 12 d of grains, 5 s of flow
/// averaged over the last 2.5 s; about 18 s of CPU): the DEM's mu(I) and phi(I) fitted
/// over its bulk (2 d above the rough bottom to 2 d under the surface), then the Eulerian
/// solver run with the scene's mu_i and with the fitted one.
///
/// * In steady uniform flow mu = tan(alpha) at every height (momentum balance), so one
///   inclination determines one point of mu(I): the fit must report the full fits as
///   unsupported and keep the level (mu_s, mu_2 and I0 held).
/// * With the fitted level, the Eulerian layer solves mu(I) = tan(alpha) at the I the DEM
///   flows at: its bulk I within 5 % of the DEM's mean bulk I (the level of a fit over
///   the bulk cells is that of their mean; the DEM's I rises by half towards the surface,
///   so its median is no measure of it). The fit's standard
///   error on mu_s (about 0.005 on this run) moves I by dI/dmu = (I0 + I)^2 / (I0 (mu_2 -
///   mu_s)) = 1.8 times it, i.e. 0.009 or 4.5 % of I = 0.19, so 5 % is the fit's own
///   precision.
/// * The scene's constants (Maurin et al. 2016, mu_s = 0.35) give I = 0.16 at tan(25 deg):
///   more than twice as far from the DEM's.
/// * The flow rate of the fitted Eulerian layer within 25 % of the DEM's: the DEM's rough
///   bottom shears its lowest 2 d at a third of the bulk's I (non-local, beyond any
///   local rheology) where the Eulerian no-slip bottom shears at the bulk I; over 12 d
///   that bottom zone adds about 0.1 m/s to every height above it, 12 % of the flux of the
///   full scene (docs/diagnostics.md); and this short layer still accelerates (its mean
///   stress ratio 0.9 % under tan(alpha), its flux 4 % under that of 10 s of flow), which
///   the steady Eulerian layer does not. Measured: 22 %.
#[test]
fn closures_fitted_on_a_dem_incline_give_the_eulerian_its_inertial_number() {
    let dir = tmp_dir("fit_loop");
    let dem = dir.join("dem");
    let o = saltus(&[
        "run",
        INCLINE,
        "--set",
        "solver.lagrangian.length=0.03",
        "--set",
        "solver.lagrangian.width=0.03",
        "--set",
        "solver.lagrangian.end_time=5.0",
        "--set",
        "solver.lagrangian.stats_start=2.5",
        "--set",
        "solver.lagrangian.threads=1",
        "--out",
        dem.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let cells = columns(&dem);
    let surface = cells.iter().filter(|c| c.1 > 0.1).map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
    let (z_min, z_max) = (2.0 * D, surface - 2.0 * D);
    let bulk = |c: &[(f64, f64, f64)]| {
        mean(c.iter().filter(|c| c.0 >= z_min && c.0 <= z_max && c.1 > 0.1).map(|c| c.2).collect())
    };
    let i_dem = bulk(&cells);

    let o = saltus(&[
        "diagnose",
        dem.to_str().unwrap(),
        "--fit",
        "--z-min",
        &z_min.to_string(),
        "--z-max",
        &z_max.to_string(),
    ]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}{text}", stderr(&o));
    // one inclination: the three-parameter fit of mu(I) cannot be supported, and says why
    assert!(text.contains("mu(I) (mu_s, mu_2, i0): not fitted:"), "{text}");
    let fitted = dem.join("diagnose").join("fitted.toml");
    let doc: toml::Table = std::fs::read_to_string(&fitted).unwrap().parse().unwrap();
    let g = &doc["closures"]["granular"];
    assert_eq!(g["type"].as_str(), Some("mu_i"));
    let q = doc["fit"]["quantity"].as_array().unwrap();
    let mu = q.iter().find(|q| q["quantity"].as_str() == Some("mu(I)")).expect("a fit of mu(I)");
    let stderr_mu_s = mu["stderr"][0].as_float().unwrap();
    assert!(stderr_mu_s > 0.0 && stderr_mu_s < 0.02, "{mu}");

    let mut runs = Vec::new();
    for (name, closures) in [("scene", None), ("fitted", Some(&fitted))] {
        let out = dir.join(name);
        let mut args: Vec<String> = vec!["run".into(), INCLINE.into()];
        for s in EULERIAN {
            args.extend(["--set".into(), s.into()]);
        }
        if let Some(f) = closures {
            args.extend(["--closures".into(), f.display().to_string()]);
        }
        args.extend(["--out".into(), out.display().to_string(), "-q".into()]);
        let o = saltus(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(o.status.success(), "{}", stderr(&o));
        runs.push(out);
    }
    let resolved = std::fs::read_to_string(runs[1].join("scene.toml")).unwrap();
    assert!(resolved.contains("closures_file = "), "the resolved scene records the closures file");
    let i_scene = bulk(&columns(&runs[0]));
    let i_fit = bulk(&columns(&runs[1]));
    let (e_fit, e_scene) = ((i_fit / i_dem - 1.0).abs(), (i_scene / i_dem - 1.0).abs());
    assert!(e_fit < 0.05, "bulk I: DEM {i_dem}, fitted {i_fit}");
    assert!(e_scene > 2.0 * e_fit, "bulk I: DEM {i_dem}, scene {i_scene}, fitted {i_fit}");
    let qs = |d: &Path| summary(d)["qs"].as_f64().unwrap();
    let (q_dem, q_fit) = (qs(&dem), qs(&runs[1]));
    assert!((q_fit / q_dem - 1.0).abs() < 0.25, "qs: DEM {q_dem}, fitted {q_fit}");
}

/// A closures file is refused, by `run` and `check` alike, naming the file and the key:
/// an unknown family, an unknown key of a model, an unknown top-level key; its `[fit]`
/// table is metadata and accepted.
#[test]
fn a_closures_file_with_an_unknown_family_or_key_is_refused_naming_both() {
    let dir = tmp_dir("closures_file_refused");
    let scene = write(&dir, "scene.toml", &format!("{BASE}{RUNNABLE}"));
    let cases = [
        ("family.toml", "[closures.granulr]\ntype = \"mu_i\"\n", "closures.granulr"),
        ("key.toml", "[closures.granular]\ntype = \"mu_i\"\nmu_z = 0.3\n", "closures.granular.mu_z"),
        ("top.toml", "[closures.granular]\ntype = \"mu_i\"\n[fitted]\na = 1\n", "fitted"),
        ("range.toml", "[closures.granular]\ntype = \"mu_i\"\nmu_s = -1.0\n", "closures.granular.mu_s"),
    ];
    for (name, text, key) in cases {
        let file = write(&dir, name, text);
        for command in ["run", "check"] {
            let out = dir.join("out");
            let mut args = vec![command, scene.to_str().unwrap(), "--closures", file.to_str().unwrap()];
            if command == "run" {
                args.extend(["--out", out.to_str().unwrap(), "-q"]);
            }
            let err = assert_clean_failure(&saltus(&args));
            assert!(
                err.contains(&file.display().to_string()) && err.contains(&format!("`{key}`")),
                "{command} {name}: {err}"
            );
            assert!(!out.join("summary.json").exists(), "{command} {name}: a refused file runs nothing");
        }
    }
    let ok = write(&dir, "ok.toml", "[closures.granular]\ntype = \"mu_i\"\nmu_s = 0.3\n[fit]\nruns = [\"x\"]\n");
    let o = saltus(&["check", scene.to_str().unwrap(), "--closures", ok.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("mu_s = 0.3") && text.contains("closures_file = "), "{text}");
}

/// An Eulerian run's fields hold its own closure exactly (docs/diagnostics.md, "The
/// Eulerian solver's fields"), so `--fit` must give that closure's parameters back through
/// profiles.csv (11 significant digits): Fry's Couette bedload with mu_k (mu_1 = 0.23,
/// mu_2 = 0.75, sqrt(K0) = 0.18 over K = 1e-7 - 40) and Chassagne's case 1 with the
/// proposed kinetic closure (a of eq 3.2 = eq 3.3 at mu_p = 0.4: 0.58 + 3.12 tanh(0.4 /
/// 0.54) = 2.5443), each within 1e-6 relative.
#[test]
fn a_fit_on_an_eulerian_run_gives_its_own_closure_back() {
    let dir = tmp_dir("fit_own_closure");
    type Case<'a> = (&'a str, &'a [&'a str], &'a [(&'a str, f64)]);
    let cases: [Case; 2] = [
        ("cases/fry2024/couette_bedload.toml", &[], &[("mu_1", 0.23), ("mu_2", 0.75), ("sqrt_k0", 0.18)]),
        (CASE01, &["--set", "domain.cells=60"], &[("a", 0.58 + (3.70 - 0.58) * (0.4f64 / 0.54).tanh())]),
    ];
    for (k, (scene, set, expected)) in cases.iter().enumerate() {
        let out = dir.join(format!("run{k}"));
        let mut args = vec!["run", scene];
        args.extend(*set);
        args.extend(["--out", out.to_str().unwrap(), "-q"]);
        let o = saltus(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let o = saltus(&["diagnose", out.to_str().unwrap(), "--fit"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let doc: toml::Table =
            std::fs::read_to_string(out.join("diagnose").join("fitted.toml")).unwrap().parse().unwrap();
        let g = &doc["closures"]["granular"];
        for (name, want) in *expected {
            let got = if *name == "a" { g["g0"]["a"].as_float() } else { g[*name].as_float() }.unwrap();
            assert!((got / want - 1.0).abs() < 1e-6, "{scene}: {name} = {got}, expected {want}");
        }
    }
}
