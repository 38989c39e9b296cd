//! `particles.wall_friction`: the friction coefficient of the grains on the flat walls of
//! the DEM (side walls, flat bottom), default the interparticle friction. A sphere
//! sliding on the wall decelerates at mu_w g (Coulomb) and ends rolling at 5/7 of its
//! speed whatever mu_w > 0; mu_w = 0 keeps its speed and makes no spin; a value out of
//! range is refused with the key. Run with `cargo test --release -p saltus-solvers --test
//! particle_wall_friction`.

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::Stepper;

fn sliding(set: &[&str]) -> Result<Scene, String> {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/verification/dem_sliding_sphere.toml");
    let mut set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    set.push("solver.lagrangian.end_time=1.0".into());
    Scene::from_file_with(file, &set).map_err(|e| e.to_string())
}

/// Speed and spin after `t` s of sliding (from v0 = 1 m/s on the wall, the scene's bead
/// friction 0.4).
fn after(scene: &Scene, t: f64) -> (f64, f64) {
    let mut m = Lagrangian::new(scene, Config::from_scene(scene).expect("config")).expect("solver");
    m.deposit().expect("deposition");
    while m.time() < t {
        assert!(m.step_unit().is_none());
    }
    (m.particles().vx[0], m.particles().wy[0])
}

#[test]
fn the_wall_friction_sets_the_sliding_deceleration_and_zero_slides_freely() {
    let (g, v0, r) = (9.81, 1.0, 3.0e-3);
    for mu in [0.1, 0.2] {
        let s = sliding(&[&format!("particles.wall_friction={mu}")]).expect("scene");
        // sliding ends at 2 v0 / (7 mu g); measured at half of it
        let t = v0 / (7.0 * mu * g);
        let (v, w) = after(&s, t);
        let decel = (v0 - v) / t;
        println!("mu_w = {mu}: deceleration {decel} against {}", mu * g);
        assert!((decel / (mu * g) - 1.0).abs() < 0.01, "mu_w {mu}: deceleration {decel}");
        assert!((w * r / (2.5 * mu * g * t) - 1.0).abs() < 0.01, "spin {w}");
        // then rolling at 5/7 v0, as with any friction
        let (v, _) = after(&s, 4.0 * t);
        assert!((v / (5.0 / 7.0 * v0) - 1.0).abs() < 0.01, "rolling speed {v}");
    }
    let s = sliding(&["particles.wall_friction=0"]).expect("scene");
    let (v, w) = after(&s, 0.1);
    assert!((v - v0).abs() < 1e-9 && w.abs() < 1e-9, "frictionless wall: v {v}, spin {w}");
}

#[test]
fn a_wall_friction_out_of_range_is_refused_with_its_key() {
    for bad in ["-0.1", "3.0", "nan"] {
        let e = sliding(&[&format!("particles.wall_friction={bad}")]).expect_err(bad);
        assert!(e.contains("particles.wall_friction"), "{bad}: {e}");
    }
}
