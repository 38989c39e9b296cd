//! Temporal order of the time-accurate stepping (`solver.eulerian.time_stepping =
//! "accurate"`, BDF2) for the granular temperature and the volume fraction (the momentum's
//! is checked on the Stokes layer, `stokes_layer.rs`; k and omega's against decaying
//! turbulence in the column's unit tests).
//!
//! The case: grains in still fluid without gravity, kinetic theory, Stokes drag, a smooth
//! initial volume fraction phi = 0.3 + 0.05 cos(pi z / H) and a uniform initial
//! temperature 1e-3 m^2/s^2. The granular temperature cools by the collisional and drag
//! dissipation (Haff's cooling, dT/dt = -(A sqrt(T) + B) T where phi is uniform), and the
//! kinetic pressure gradient spreads phi towards uniformity: both fields evolve smoothly
//! (T falls to 0.6-0.8 of its start over the 2 ms), no flow is driven. The errors at dt,
//! dt/2 and dt/4 (dt = 0.1 ms) against a run at dt/64 give the order: 2 within 0.25 for
//! each field (backward Euler's is 1), and the sediment mass is kept to round-off.

use std::path::Path;

use saltus_core::scene::{parse_table, Scene};
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{Ending, Stepper, WarmStart};
use saltus_solvers::Profiles;

const HEIGHT: f64 = 0.02;
const CELLS: usize = 40;
const END: f64 = 0.002;
/// amplitude of the initial cosine of phi
const AMP: f64 = 0.05;

fn scene(steps: usize) -> Scene {
    saltus_closures::link();
    let text = format!(
        r#"
[fluid]
density = 1000.0
viscosity = 1.0e-6
[particles]
diameter = 1.0e-3
density = 2650.0
restitution = 0.7
[physics]
gravity = 0.0
[domain]
bed_height = {HEIGHT:e}
bed_phi = 0.3
water_depth = 0.0
cells = {CELLS}
[solver]
type = "eulerian"
[solver.eulerian]
time_stepping = "accurate"
initial_temperature = 1.0e-3
dt_initial = {dt:e}
dt_max = {dt:e}
end_time = {END}
[closures.granular]
type = "frictional_collisional"
[closures.drag]
type = "stokes"
[closures.turbulence]
type = "laminar"
"#,
        dt = END / steps as f64,
    );
    let t = parse_table(&text, Path::new("cooling.toml")).expect("toml");
    Scene::from_table(t, Path::new("cooling.toml")).expect("scene")
}

/// (phi, T) at the end time, and the relative change of the sediment height.
fn run(steps: usize) -> (Vec<f64>, Vec<f64>, f64) {
    let s = scene(steps);
    let cfg = Config::from_scene(&s).expect("config");
    let mut m = Eulerian::new(&s, cfg).expect("solver");
    let z = m.z().to_vec();
    let mut p = Profiles::default();
    p.push("z", z.clone());
    p.push("u_f", vec![0.0; CELLS]);
    p.push("phi", z.iter().map(|z| 0.3 + AMP * (std::f64::consts::PI * z / HEIGHT).cos()).collect());
    m.warm_start(&WarmStart::Profiles(p)).expect("warm start");
    let h0 = m.sediment_height();
    let ending = loop {
        if let Some(e) = m.step_unit() {
            break e;
        }
    };
    assert_eq!(ending, Ending::EndTime);
    assert_eq!(m.steps(), steps, "the step stays at dt_max");
    (m.phi().to_vec(), m.temperature().to_vec(), (m.sediment_height() - h0).abs() / h0)
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

#[test]
fn temperature_and_volume_fraction_are_second_order_in_time() {
    let (phi_ref, t_ref, mass) = run(20 * 64);
    assert!(mass < 1e-13, "sediment height changed by {mass:e}");
    let runs = [20, 40, 80].map(run);
    let e_phi = runs.clone().map(|r| max_rel(&r.0, &phi_ref));
    let e_t = runs.map(|r| max_rel(&r.1, &t_ref));
    // the case moves: phi spreads, T cools by a large factor
    let t0 = 1.0e-3;
    println!(
        "T(end)/T0 = {:.3}..{:.3}",
        t_ref.iter().cloned().fold(f64::MAX, f64::min) / t0,
        t_ref.iter().cloned().fold(0.0, f64::max) / t0
    );
    println!(
        "phi range at the end {:.4}..{:.4}",
        phi_ref.iter().cloned().fold(f64::MAX, f64::min),
        phi_ref.iter().cloned().fold(0.0, f64::max)
    );
    let fields = [("phi", e_phi), ("theta_g", e_t)];
    for (name, e) in fields {
        let p = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
        println!("{name}: errors {e:?} at dt, dt/2, dt/4; orders {p:.3?}");
    }
    for (name, e) in fields {
        let p = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
        for q in p {
            assert!((q - 2.0).abs() < 0.25, "{name}: order {q} (errors {e:?})");
        }
    }
}
