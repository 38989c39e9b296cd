//! The Frey bottoms of the DEM (Maurin et al. 2015 section III A-B,
//! `solver.lagrangian.bottom = "half_cylinders" | "bead_row"`): a sphere in the pocket of
//! two cylinders rests at the height of the force balance; a sphere dropped on a crest
//! bounces with the restitution coefficient; an elastic frictionless oblique impact keeps
//! the energy and reflects the velocity about the normal; the elevations lie in the
//! paper's set; the runs are bit-identical on one and two threads; bad input is refused
//! with the key. Run with `cargo test --release -p saltus-solvers --test frey_bottom`.

mod common;

use std::path::Path;

use saltus_core::scene::{Scene, FREY_LEVELS};
use saltus_solvers::lagrangian::{Box3, Config, ContactLaw, Dem, HalfCylinders, Lagrangian, Particles};
use saltus_solvers::run::{drive, Ending, Quiet};

const D: f64 = 6.0e-3;
const RHO: f64 = 2500.0;
const KN: f64 = 5.0e3;

fn mass() -> f64 {
    RHO * saltus_core::grain::sphere_volume(D)
}

/// A DEM of one mobile sphere over `cyl`, no walls, x periodic over the cylinders.
fn one_sphere(cyl: HalfCylinders, x: [f64; 3], v: [f64; 3], law: ContactLaw, g: f64, dt: f64) -> Dem {
    let mut p = Particles::default();
    p.push(x, v, [0.0; 3], 0.5 * D, RHO, false);
    let bx = Box3 { length: [cyl.period(), 1.0, 0.0], periodic: [true, false, false] };
    Dem::new(p, bx, law, Vec::new(), [0.0, 0.0, -g], dt, 0.1 * D).with_cylinders(Some(cyl))
}

/// The contact time of a sphere against a fixed body, pi sqrt(m / k_n) (undamped).
fn contact_time() -> f64 {
    std::f64::consts::PI * (mass() / KN).sqrt()
}

#[test]
fn a_sphere_in_the_pocket_of_two_cylinders_rests_at_the_force_balance_height() {
    // two cylinders 1.2 d apart at the same height z0; at rest on both, the centre is
    // h = sqrt((d - delta)^2 - (s/2)^2) above the axes with 2 k_n delta cos(a) = m g,
    // cos(a) = h / (d - delta) (solved by fixed point); frictionless, so that the normal
    // springs alone hold m g (with friction the tangential springs loaded while the
    // sphere sinks into the pocket take a share)
    let (s, z0, g) = (1.2 * D, 0.01, 9.81);
    let cyl = HalfCylinders { radius: 0.5 * D, spacing: s, z: vec![z0, z0, z0, z0] };
    let law = ContactLaw::linear(KN, 0.5 * KN, 0.5, 0.0);
    let dt = 0.02 * contact_time();
    let mut delta = 0.0;
    for _ in 0..50 {
        let h = ((D - delta) * (D - delta) - 0.25 * s * s).sqrt();
        delta = mass() * g / (2.0 * KN * h / (D - delta));
    }
    let h = ((D - delta) * (D - delta) - 0.25 * s * s).sqrt();
    // released 0.1 mm above its resting place, between cylinders 1 and 2
    let mut dem = one_sphere(cyl, [2.0 * s, 0.5, z0 + h + 1.0e-4], [0.0; 3], law, g, dt);
    let steps = (1.0 / dt) as usize;
    for _ in 0..steps {
        dem.step();
    }
    let p = dem.particles();
    let err = (p.z[0] - (z0 + h)).abs();
    println!("rest height {:.9e} against {:.9e}: error {err:.2e} m, overlap {delta:.3e} m", p.z[0], z0 + h);
    assert!(err < 0.01 * delta, "rest height error {err} against the overlap {delta}");
    assert!((p.x[0] - 2.0 * s).abs() < 1e-12 && p.vz[0].abs() < 1e-6, "x {} vz {}", p.x[0], p.vz[0]);
    // the two normal springs store 2 k_n delta^2 / 2
    let e = dem.normal_spring_energy();
    assert!((e / (KN * delta * delta) - 1.0).abs() < 0.02, "spring energy {e}");
}

#[test]
fn a_sphere_dropped_on_a_crest_bounces_with_the_restitution_coefficient() {
    // head-on impact at 0.2 m/s on the crest of a cylinder, no gravity: v_z' = -e v_z
    // within 1 %, no sideways velocity and no spin
    for e in [0.3, 0.5, 0.9] {
        let cyl = HalfCylinders { radius: 0.5 * D, spacing: 10.0 * D, z: vec![0.01] };
        let law = ContactLaw::linear(KN, 0.5 * KN, e, 0.4);
        let dt = 0.005 * contact_time();
        let x = [5.0 * D, 0.5, 0.01 + D + 1.0e-5];
        let mut dem = one_sphere(cyl, x, [0.0, 0.0, -0.2], law, 0.0, dt);
        let steps = ((1.0e-5 / 0.2 + 2.0 * contact_time()) / dt) as usize;
        for _ in 0..steps {
            dem.step();
        }
        let p = dem.particles();
        println!("e = {e}: measured {}", p.vz[0] / 0.2);
        assert!((p.vz[0] / (0.2 * e) - 1.0).abs() < 0.01, "e = {e}: v_z after {}", p.vz[0]);
        assert!(p.vx[0].abs() < 1e-12 && p.wy[0].abs() < 1e-9, "vx {} wy {}", p.vx[0], p.wy[0]);
    }
}

#[test]
fn an_elastic_frictionless_oblique_impact_keeps_the_energy_and_reflects_the_velocity() {
    // a sphere falling at 0.3 m/s onto the shoulder of a cylinder, 0.3 d off its axis,
    // e = 1 and mu = 0: the kinetic energy is kept (0.1 %), no spin is made, and the
    // velocity is reflected about the contact normal n = (sin a, 0, cos a), sin a = 0.3
    // (the normal turns by the overlap over d during the contact, 1e-3 here)
    let cyl = HalfCylinders { radius: 0.5 * D, spacing: 10.0 * D, z: vec![0.01] };
    let law = ContactLaw::linear(KN, 0.5 * KN, 1.0, 0.0);
    let dt = 0.005 * contact_time();
    let sin_a: f64 = 0.3;
    let cos_a = (1.0 - sin_a * sin_a).sqrt();
    // the axis at x = spacing / 2
    let (x0, v0) = (5.0 * D, 0.3);
    let x = [x0 - sin_a * D, 0.5, 0.01 + cos_a * D + 1.0e-5];
    let mut dem = one_sphere(cyl, x, [0.0, 0.0, -v0], law, 0.0, dt);
    for _ in 0..((1.0e-5 / v0 / cos_a + 2.0 * contact_time()) / dt) as usize {
        dem.step();
    }
    let p = dem.particles();
    let v = [p.vx[0], p.vz[0]];
    let energy = (v[0] * v[0] + v[1] * v[1]) / (v0 * v0);
    // v' = v - 2 (v.n) n with v = (0, -v0), n = (-sin a, -cos a) from the sphere to the axis
    let expect = [-2.0 * v0 * cos_a * sin_a, -v0 + 2.0 * v0 * cos_a * cos_a];
    println!("after: {v:?}, reflected {expect:?}, energy ratio {energy}");
    assert!((energy - 1.0).abs() < 1e-3, "energy ratio {energy}");
    assert!((v[0] - expect[0]).abs() < 0.01 * v0 && (v[1] - expect[1]).abs() < 0.01 * v0, "{v:?} vs {expect:?}");
    assert!(p.wx[0].abs() + p.wy[0].abs() + p.wz[0].abs() < 1e-9, "spin without friction");
}

fn frey_scene(set: &[&str]) -> Scene {
    saltus_closures::link();
    let mut all = vec![
        "solver.lagrangian.length=0.12",
        "solver.lagrangian.particles=140",
        "solver.lagrangian.settle_time=0.2",
        "solver.lagrangian.end_time=0.2",
        "solver.lagrangian.stats_start=0.0",
        "solver.lagrangian.cells=60",
        "domain.water_depth=0.012",
    ];
    all.extend_from_slice(set);
    let all: Vec<String> = all.iter().map(|s| s.to_string()).collect();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/maurin2015/frey_sim6.toml");
    Scene::from_file_with(file, &all).unwrap_or_else(|e| panic!("{e}"))
}

/// True when `z` is d + (k - 5.5) d / 12 for an integer k in 0..12; returns k.
fn level(z: f64) -> Option<usize> {
    let k = (z - D) * FREY_LEVELS as f64 / D + 0.5 * (FREY_LEVELS as f64 - 1.0);
    let r = k.round();
    ((k - r).abs() < 1e-9 && (0.0..FREY_LEVELS as f64).contains(&r)).then_some(r as usize)
}

#[test]
fn the_elevations_are_the_papers_set_and_fill_it() {
    // l_x = 20 d: 20 cylinders, spacing d; elevations from -2.75 to 2.75 mm around d in
    // steps of 0.5 mm; over 2000 cylinders every level is drawn, each about 1/12 of them
    let s = frey_scene(&["solver.lagrangian.bottom=half_cylinders"]);
    let m = Lagrangian::new(&s, Config::from_scene(&s).expect("config")).expect("solver");
    let c = m.dem().cylinders().expect("cylinders");
    assert_eq!(c.z.len(), 20);
    assert!((c.spacing - D).abs() < 1e-15 && (c.radius - 0.5 * D).abs() < 1e-15);
    assert!(c.z.iter().all(|&z| level(z).is_some()), "{:?}", c.z);
    let many = saltus_solvers::lagrangian::run::setup::frey_elevations(2400, D, 3);
    let mut counts = [0usize; FREY_LEVELS];
    for &z in &many {
        counts[level(z).unwrap_or_else(|| panic!("{z} not a level"))] += 1;
    }
    // binomial: 200 +- 13.5 each; 5 standard deviations
    assert!(counts.iter().all(|&n| (n as f64 - 200.0).abs() < 68.0), "{counts:?}");
    // the bead row: one fixed bead per diameter along x (one across 6.5 d / 6), same set
    let s = frey_scene(&["solver.lagrangian.bottom=bead_row"]);
    let m = Lagrangian::new(&s, Config::from_scene(&s).expect("config")).expect("solver");
    let p = m.particles();
    assert_eq!(p.len() - p.n_mobile, 20);
    assert!((p.n_mobile..p.len()).all(|k| level(p.z[k]).is_some() && (p.y[k] - 3.25e-3).abs() < 1e-12));
    assert!(m.dem().cylinders().is_none());
}

fn bits_after_run(s: &Scene, threads: usize) -> Vec<u64> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| {
        let mut m = Lagrangian::new(s, Config::from_scene(s).expect("config")).expect("solver");
        let ending = drive(&mut m, &mut Quiet).ending;
        assert_eq!(ending, Ending::EndTime);
        let p = m.particles();
        let mut bits: Vec<u64> = Vec::new();
        for v in [&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz] {
            bits.extend(v.iter().map(|x| x.to_bits()));
        }
        bits.extend(m.fluid_velocity().iter().map(|x| x.to_bits()));
        bits
    })
}

#[test]
fn a_coupled_run_on_half_cylinders_is_bit_identical_on_one_and_two_threads_and_rests_on_them() {
    // more than one work item of mobile particles (CHUNK = 256)
    let s = frey_scene(&["solver.lagrangian.bottom=half_cylinders", "solver.lagrangian.particles=600"]);
    let one = bits_after_run(&s, 1);
    let two = bits_after_run(&s, 2);
    assert_eq!(one, two, "1 and 2 threads differ");
    // no bead sinks between or through the cylinders: no overlap beyond 2 % of d (the
    // softness under a column of 30 beads is about 0.2 %)
    let m = {
        let mut m = Lagrangian::new(&s, Config::from_scene(&s).expect("config")).expect("solver");
        let ending = drive(&mut m, &mut Quiet).ending;
        assert_eq!(ending, Ending::EndTime);
        m
    };
    let c = m.dem().cylinders().expect("cylinders").clone();
    let p = m.particles();
    let period = c.period();
    for k in 0..p.n_mobile {
        for (j, &z) in c.z.iter().enumerate() {
            let dx = ((j as f64 + 0.5) * c.spacing - p.x[k] + 0.5 * period).rem_euclid(period) - 0.5 * period;
            let dist = (dx * dx + (z - p.z[k]).powi(2)).sqrt();
            assert!(dist > 0.98 * D, "bead {k} {dist} from axis {j}");
        }
    }
}

#[test]
fn frey_bottoms_are_refused_where_they_cannot_work_with_the_key_named() {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/maurin2015/frey_sim6.toml");
    let load = |set: &[&str]| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        Scene::from_file_with(&file, &set).map(|_| ()).map_err(|e| e.to_string())
    };
    let e = load(&["solver.lagrangian.bottom=cylinders"]).expect_err("unknown bottom");
    assert!(e.contains("solver.lagrangian.bottom") && e.contains("half_cylinders"), "{e}");
    let e = load(&[
        "solver.lagrangian.bottom=half_cylinders",
        "solver.lagrangian.initial=gas",
        "solver.lagrangian.height=0.05",
        "solver.lagrangian.gas_phi=0.1",
        "solver.lagrangian.gas_temperature=0.01",
    ])
    .expect_err("gas over cylinders");
    assert!(e.contains("solver.lagrangian.bottom") && e.contains("gas"), "{e}");
    assert!(load(&["solver.lagrangian.bottom=bead_row"]).is_ok());
    let _ = common::SMALL_COUPLED_BED;
}
