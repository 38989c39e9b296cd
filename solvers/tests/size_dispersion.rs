//! `solver.lagrangian.size_dispersion` (Fry et al. 2024 section II C: a 5 % dispersion of
//! the diameters "to avoid crystallization"): the grains of a deposited bed drawn
//! uniformly in [(1 - s) d, (1 + s) d], each with the mass of its own volume; 0 keeps the
//! monodisperse bed and its random stream. Checked on the released grains (before the
//! deposition).

mod common;

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};

fn bed(set: &[&str]) -> Scene {
    saltus_closures::link();
    let mut all: Vec<String> = common::SMALL_COUPLED_BED.iter().map(|s| s.to_string()).collect();
    all.extend(set.iter().map(|s| s.to_string()));
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    Scene::from_file_with(file, &all).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_dispersed_bed_draws_its_diameters_in_the_band() {
    let s = 0.05;
    let scene = bed(&["solver.lagrangian.size_dispersion=0.05"]);
    let m = Lagrangian::new(&scene, Config::from_scene(&scene).expect("config")).expect("solver");
    let p = m.particles();
    let r = 0.5 * scene.particles.diameter;
    let n = p.n_mobile;
    assert!(n > 100, "{n} grains");
    let radii = &p.radius[..n];
    // every radius in the band, the band filled (uniform: min and max within 5 % of its ends)
    assert!(radii.iter().all(|&a| a >= (1.0 - s) * r * (1.0 - 1e-12) && a <= (1.0 + s) * r * (1.0 + 1e-12)));
    let (lo, hi) = radii.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &a| (l.min(a), h.max(a)));
    assert!(lo < (1.0 - 0.9 * s) * r && hi > (1.0 + 0.9 * s) * r, "{lo} {hi}");
    // uniform: mean r within 3 standard errors (s r / sqrt(3 n)) of r
    let mean = radii.iter().sum::<f64>() / n as f64;
    assert!((mean - r).abs() < 3.0 * s * r / (3.0 * n as f64).sqrt(), "mean {mean} against {r}");
    // each grain has the mass of its own sphere
    let rho = scene.particles.density;
    for (&a, &inv) in radii.iter().zip(&p.inv_mass[..n]) {
        let m = rho * saltus_core::grain::sphere_volume(2.0 * a);
        assert!((inv * m - 1.0).abs() < 1e-12);
    }
}

#[test]
fn no_dispersion_keeps_the_monodisperse_bed() {
    let scene = bed(&[]);
    let zero = bed(&["solver.lagrangian.size_dispersion=0"]);
    let a = Lagrangian::new(&scene, Config::from_scene(&scene).expect("config")).expect("solver");
    let b = Lagrangian::new(&zero, Config::from_scene(&zero).expect("config")).expect("solver");
    let r = 0.5 * scene.particles.diameter;
    assert!(a.particles().radius.iter().all(|&x| x == r));
    assert_eq!(a.particles().x, b.particles().x);
    assert_eq!(a.particles().z, b.particles().z);
}

#[test]
fn grains_of_two_sizes_leave_no_negative_coordination_or_dissipation() {
    // solvers/tests/fixtures/dispersed_bed_coordination.toml: coordination down to -632
    // in the bed when the contact count was spread with the signed share of the stress
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/dispersed_bed_coordination.toml");
    let scene = Scene::from_file(&file).unwrap_or_else(|e| panic!("{e}"));
    let mut m = Lagrangian::new(&scene, Config::from_scene(&scene).expect("config")).expect("solver");
    let ending = saltus_solvers::run::drive(&mut m, &mut saltus_solvers::run::Quiet).ending;
    assert_eq!(ending, saltus_solvers::run::Ending::EndTime);
    let profiles = saltus_solvers::run::Stepper::report(&m, &ending, &Default::default()).profiles;
    let phi = profiles.get("phi").expect("phi");
    for key in ["coordination", "dissipation"] {
        let v = profiles.get(key).unwrap_or_else(|| panic!("no {key}"));
        let held: Vec<(usize, f64)> = v.iter().copied().enumerate().filter(|(_, x)| !x.is_nan()).collect();
        assert!(held.len() > 10, "{key}: {held:?}");
        assert!(held.iter().all(|(_, x)| *x >= 0.0 && x.is_finite()), "{key}: {held:?}");
    }
    // a packed bed: the median Z of the slices with phi above 0.5 is that of a frictional
    // packing, 4 to 7 (lower at the rough layer, whose fixed grains' contacts are not
    // computed)
    let z = profiles.get("coordination").unwrap();
    let mut dense: Vec<f64> = z.iter().zip(phi).filter(|(_, p)| **p > 0.5).map(|(z, _)| *z).collect();
    dense.sort_by(f64::total_cmp);
    assert!(dense.len() > 10 && (4.0..7.0).contains(&dense[dense.len() / 2]), "{dense:?}");
}
