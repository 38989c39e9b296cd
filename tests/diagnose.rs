//! `saltus diagnose` held to closures it must find again: Eulerian runs against their own
//! closure (the run writes its granular fields with the closure, so every comparison of
//! that closure vanishes to round-off), and synthetic DEM-like profiles built from a known
//! closure with known parameters (the same closure: RMS ~ 0; other parameters: the RMS
//! and its sign that the parameter change implies).

use std::path::{Path, PathBuf};

use saltus::diagnose::{diagnose_fields, Diagnosis, Options, RunFields};
use saltus::table::Table;
use saltus_closures::granular::kinetic::radial_distribution::friction_coefficient_a;
use saltus_closures::granular::kinetic::{RadialDistribution, Saltation};
use saltus_closures::granular::{FrictionalCollisional, MuI};
use saltus_core::scene::Scene;
use saltus_core::{KineticTheory, LocalRheology, SaltationInput};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn scene(file: &str, set: &[&str]) -> Scene {
    saltus_closures::link();
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Scene::from_file_with(root().join(file), &set).expect("scene")
}

/// Run `scene` in memory and diagnose its profiles at full precision.
fn run_and_diagnose(scene: Scene, closures: &[&str]) -> Diagnosis {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("diagnose_{}", scene.meta.name));
    let outcome = saltus_solvers::run(&scene, &dir, &mut saltus_solvers::run::Quiet).expect("run");
    assert!(matches!(outcome.ending, saltus_solvers::Ending::Steady), "{:?}", outcome.ending);
    let mut t = Table::default();
    for (name, v) in &outcome.report.profiles.columns {
        t.push(name.clone(), v.clone());
    }
    let d = diagnose_with(t, scene, closures);
    println!("{}", d.text());
    d
}

fn diagnose_with(t: Table, scene: Scene, closures: &[&str]) -> Diagnosis {
    let mut f = RunFields::new(PathBuf::from("memory/profiles.csv"), t, scene).expect("fields");
    let args: Vec<String> = closures.iter().map(|s| s.to_string()).collect();
    diagnose_fields(&mut f, &args, Options::default()).expect("diagnose")
}

fn assert_vanishes(d: &Diagnosis, label: &str, quantity: &str, tol: f64, min_cells: usize) {
    let c = d.find(label, quantity).unwrap_or_else(|| panic!("no {label} {quantity}:\n{}", d.text()));
    assert!(c.cells() >= min_cells, "{label} {quantity}: {} cells\n{}", c.cells(), d.text());
    assert!(c.relative_rms() <= tol, "{label} {quantity}: relative RMS {}\n{}", c.relative_rms(), d.text());
}

/// Chassagne case 1 (proposed kinetic model, saltation, Jenkins-Zhang, quadratic drag
/// dissipation) at 60 cells, diagnosed with its own closure: g0, Gamma, the viscosity
/// F2, the heat flux and J_int of eq 3.13 (the closure's) within 1e-10 relative.
#[test]
fn eulerian_kinetic_run_against_its_own_closure() {
    let d = run_and_diagnose(scene("cases/chassagne2023/case01.toml", &["domain.cells=60"]), &[]);
    let label = "frictional_collisional";
    for q in ["Gamma", "heat flux", "J_int eq 3.13"] {
        assert_vanishes(&d, label, q, 1e-10, 10);
    }
    // g0 and F2 only above the packed bed (the highest cell with an elastic pressure)
    for q in ["g0 closure", "g0 chialvo_sundaresan_friction", "viscosity F2"] {
        assert_vanishes(&d, label, q, 1e-10, 5);
    }
    // eq 3.13 dissipates more than eq 2.25 (c_J > 3): the linear closure under-predicts
    let linear = d.find(label, "J_int eq 2.25").expect("eq 2.25");
    assert!(linear.relative_bias() > 0.05, "{}", d.text());
    // a of eq 3.2 fitted to the g0 the run's pressure holds: eq 3.3 at mu_p = 0.4
    let fit = d.closures[0].g0_fit.expect("fit");
    let a = friction_coefficient_a(0.4, 0.58, 3.70, 0.54);
    assert!((fit.a - a).abs() <= 1e-9 * a, "{} vs {a}", fit.a);
}

/// The dry mu(I) incline (benchmark 6) against mu_i: mu(I) of the closure exactly. phi(I)
/// is not: the Eulerian pressure adds the Johnson-Jackson elastic part and the surface
/// overburden to the dilatancy pressure of phi(I) (docs/eulerian.md), a few 1e-4 here.
#[test]
fn eulerian_mu_i_run_against_its_own_closure() {
    let d = run_and_diagnose(scene("cases/verification/dry_mu_i_incline.toml", &[]), &[]);
    assert_vanishes(&d, "mu_i", "mu(I)", 1e-10, 50);
    let phi = d.find("mu_i", "phi(I)").expect("phi(I)");
    assert!(phi.relative_rms() < 1e-3, "{}", d.text());
}

/// Fry 2024 laminar Couette bedload against mu_k (its own) and mu_i.
#[test]
fn eulerian_mu_k_run_against_its_own_closure() {
    let d = run_and_diagnose(scene("cases/fry2024/couette_bedload.toml", &[]), &["type = \"mu_k\""]);
    assert_vanishes(&d, "mu_k", "mu(K)", 1e-10, 50);
}

/// DEM-like profiles of a mu(I) material: cells at I from 1e-3 to 1 under a pressure
/// rising with depth, mu and phi of mu_i with its defaults.
fn mu_i_profiles() -> Table {
    let m = MuI::default();
    let (d, rho_p) = (6e-3, 2500.0);
    let n = 40;
    let mut cols: [Vec<f64>; 6] = Default::default();
    for k in 0..n {
        let i = 10f64.powf(-3.0 + 3.0 * k as f64 / (n - 1) as f64);
        let p = 50.0 * (n - k) as f64;
        let gamma = i * (p / rho_p).sqrt() / d;
        for (c, v) in cols.iter_mut().zip([d * (k as f64 + 0.5), m.packing(i), p, gamma, m.friction(i), 0.0]) {
            c.push(v);
        }
    }
    let mut t = Table::default();
    for (name, c) in ["z", "phi", "p_p", "gamma_dot", "mu_eff", "u_p"].into_iter().zip(cols) {
        t.push(name, c);
    }
    t
}

/// Synthetic mu(I) profiles: mu_i with the parameters that built them gives RMS 0; with
/// mu_s and mu_2 both 0.05 lower, mu(I) is 0.05 lower in every cell, an RMS of 0.05 with
/// a negative bias, and phi(I) is unchanged.
#[test]
fn synthetic_mu_i_profiles_recover_their_closure() {
    let s = scene("cases/chassagne2023/case01.toml", &[]);
    let d = diagnose_with(
        mu_i_profiles(),
        s,
        &["[same]\ntype = \"mu_i\"\n[lower]\ntype = \"mu_i\"\nmu_s = 0.30\nmu_2 = 0.92"],
    );
    assert_vanishes(&d, "same", "mu(I)", 1e-14, 40);
    assert_vanishes(&d, "same", "phi(I)", 1e-14, 40);
    let lower = d.find("lower", "mu(I)").expect("lower");
    assert!((lower.rms() - 0.05).abs() < 1e-12, "{}", lower.rms());
    assert!(lower.relative_bias() < 0.0);
    assert_vanishes(&d, "lower", "phi(I)", 1e-14, 40);
}

/// DEM-like kinetic profiles of closure `kt` (phi from 0.15 to 0.6, T linear in z so that
/// the central difference of dT/dz is exact, a shear rate, beta): every field written as
/// the closure and eq 2.25 give it.
fn kinetic_profiles(kt: &dyn KineticTheory) -> Table {
    let (d, rho_p) = (6e-3, 2500.0);
    let n = 30;
    let names = [
        "z",
        "phi",
        "theta_g",
        "p_p",
        "gamma_dot",
        "mu_eff",
        "dissipation",
        "heat_flux",
        "beta",
        "drag_dissipation",
        "u_f",
        "u_p",
    ];
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let dtdz = 2.0;
    for k in 0..n {
        let z = d * (k as f64 + 0.5);
        let phi = 0.6 - 0.45 * k as f64 / (n - 1) as f64;
        let t = 1e-3 + dtdz * z;
        let beta = 300.0 * phi;
        let s = SaltationInput {
            sqrt_t: t.sqrt(),
            k_drag: beta / (phi * (1.0 - phi)),
            particle_density: rho_p,
            diameter: d,
        };
        let c = kt.coefficients(phi, kt.saltation_enabled().then_some(&s));
        let p = kt.elastic_pressure(phi) + rho_p * c.f1 * t;
        let gamma = 20.0;
        let tau = rho_p * d * c.f2 * t.sqrt() * gamma + kt.static_friction() * kt.elastic_pressure(phi);
        let values = [
            z,
            phi,
            t,
            p,
            gamma,
            tau / p,
            rho_p / d * c.f4 * t.powf(1.5),
            -rho_p * d * c.f3 * t.sqrt() * dtdz,
            beta,
            -3.0 * beta * t,
            0.5,
            0.3,
        ];
        for (col, v) in cols.iter_mut().zip(values) {
            col.push(v);
        }
    }
    let mut t = Table::default();
    for (name, c) in names.into_iter().zip(cols) {
        t.push(name, c);
    }
    t
}

/// Synthetic kinetic profiles of the proposed model (e = 0.7, mu_p = 0.4, saltation on):
/// the same closure finds every field again; with e = 0.9 the collisional dissipation is
/// predicted (1 - e_eff'^2) / (1 - e_eff^2) times the measured in every cell (the g0 and
/// phi being the same): a relative RMS of 1 minus that ratio, and a negative bias.
#[test]
fn synthetic_kinetic_profiles_recover_their_closure() {
    let proposed = FrictionalCollisional::default();
    let t = kinetic_profiles(&proposed);
    let s = scene("cases/chassagne2023/case01.toml", &[]);
    let d = diagnose_with(
        t,
        s,
        &["[same]\ntype = \"frictional_collisional\"\n[elastic]\ntype = \"frictional_collisional\"\nrestitution = 0.9"],
    );
    for q in ["g0 closure", "g0 chialvo_sundaresan_friction", "Gamma", "heat flux", "J_int eq 2.25"] {
        assert_vanishes(&d, "same", q, 1e-12, 20);
    }
    assert_vanishes(&d, "same", "viscosity F2", 1e-12, 20);
    let e_eff =
        |e: f64| FrictionalCollisional { restitution: e, ..FrictionalCollisional::default() }.effective_restitution();
    let ratio = (1.0 - e_eff(0.9).powi(2)) / (1.0 - e_eff(0.7).powi(2));
    let gamma = d.find("elastic", "Gamma").expect("Gamma");
    assert!((gamma.relative_rms() - (1.0 - ratio)).abs() < 1e-12, "{} vs {}", gamma.relative_rms(), 1.0 - ratio);
    assert!(gamma.relative_bias() < 0.0);
    // eq 3.13 dissipates more than the eq 2.25 the profiles hold
    assert!(d.find("same", "J_int eq 3.13").expect("3.13").relative_bias() < 0.0);
}

/// g0 round trip: the pressure of a closure with a given radial distribution gives that
/// g0 back, and the a of eq 3.2 fitted to it is the one it was built with (0 for
/// Carnahan-Starling, 1.7 for a Chialvo-Sundaresan a = 1.7).
#[test]
fn g0_extracted_from_the_pressure_is_the_model_that_made_it() {
    for (g0, toml, a) in [
        (RadialDistribution::CarnahanStarling {}, "g0 = { type = \"carnahan_starling\" }", 0.0),
        (
            RadialDistribution::ChialvoSundaresan(saltus_closures::granular::kinetic::ChialvoSundaresanG0 { a: 1.7 }),
            "g0 = { type = \"chialvo_sundaresan\", a = 1.7 }",
            1.7,
        ),
    ] {
        let kt = FrictionalCollisional { g0, saltation: Saltation::disabled(), ..FrictionalCollisional::default() };
        let closure = format!("type = \"frictional_collisional\"\nsaltation = {{ enabled = false }}\n{toml}");
        let d = diagnose_with(kinetic_profiles(&kt), scene("cases/chassagne2023/case01.toml", &[]), &[&closure]);
        assert_vanishes(&d, "frictional_collisional", "g0 closure", 1e-12, 20);
        let fit = d.closures[0].g0_fit.expect("fit");
        assert!((fit.a - a).abs() < 1e-10, "{} vs {a}", fit.a);
        // every band of phi holds cells and gives the same a, without scatter
        for b in fit.bands {
            assert!(b.cells >= 3 && (b.a - a).abs() < 1e-10 && b.a_stderr < 1e-10, "{b:?} vs {a}");
        }
        assert!(fit.a_stderr < 1e-10, "{}", fit.a_stderr);
        if a == 0.0 {
            assert_vanishes(&d, "frictional_collisional", "g0 carnahan_starling", 1e-12, 20);
        }
    }
}

/// The same synthetic mu(I) profiles as a run folder on disk: `profiles.csv` as a run
/// writes it (11 significant digits, an empty cell where a value is undefined, here two
/// rows above the layer without pressure) and the resolved `scene.toml`. The undefined
/// rows are not used, and the closure is found again to the precision of the file.
#[test]
fn a_run_folder_with_undefined_cells() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("diagnose_synthetic_folder");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let t = mu_i_profiles();
    let mut p = saltus_solvers::Profiles::default();
    for (name, c) in t.names.iter().zip(&t.columns) {
        let mut c = c.clone();
        // two rows of clear water: phi = 0, p_p = 0, mu_eff undefined
        let top = c.last().copied().unwrap_or(0.0);
        let extra = match name.as_str() {
            "z" => [top + 6e-3, top + 12e-3],
            "mu_eff" => [f64::NAN, f64::NAN],
            "gamma_dot" => [1.0, 1.0],
            _ => [0.0, 0.0],
        };
        c.extend(extra);
        p.push(name, c);
    }
    let csv = p.to_csv();
    assert!(csv.lines().last().unwrap().contains(",,"), "an undefined cell is empty: {csv}");
    std::fs::write(dir.join("profiles.csv"), csv).unwrap();
    let s = scene("cases/chassagne2023/case01.toml", &[]);
    std::fs::write(dir.join("scene.toml"), s.to_toml().unwrap()).unwrap();
    let d = saltus::diagnose::diagnose(&dir, &["type = \"mu_i\"".to_string()], Options::default()).expect("diagnose");
    assert_eq!(d.cells, 42);
    assert_vanishes(&d, "mu_i", "mu(I)", 1e-9, 40);
    assert_eq!(d.find("mu_i", "mu(I)").unwrap().cells(), 40);
}
