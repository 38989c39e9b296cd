//! The adapted neighbour skin in a coupled run: the skin moves, and the
//! run stays bit-identical on one and two threads and for a seed.

mod common;

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::Ending;

/// The small coupled bed of case 1 at the peer's time step (0.22 contact times) with a
/// smallest skin of 0.02 d, so that the deposition's falling grains widen it.
fn scene() -> Scene {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let mut set: Vec<String> = common::SMALL_COUPLED_BED.iter().map(|s| s.to_string()).collect();
    set.extend(
        [
            "solver.lagrangian.end_time=0.1",
            "solver.lagrangian.stats_start=0.0",
            "solver.lagrangian.dt_safety=0.22",
            "solver.lagrangian.skin=0.02",
            "closures.fluctuation={type=\"drw\"}",
        ]
        .map(String::from),
    );
    Scene::from_file_with(&file, &set).expect("scene")
}

/// The state bits after the run on `threads` threads, the skins it took (smallest,
/// largest) and its neighbour builds.
fn run(s: &Scene, threads: usize) -> (Vec<u64>, (f64, f64), usize) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| {
        let mut m = Lagrangian::new(s, Config::from_scene(s).expect("config")).expect("solver");
        let mut skins = (f64::INFINITY, 0.0f64);
        m.deposit().expect("deposition");
        loop {
            match m.step_dem() {
                Ok(_) => {}
                Err(e) => {
                    assert_eq!(e, Ending::EndTime);
                    break;
                }
            }
            let skin = m.dem().list().skin;
            skins = (skins.0.min(skin), skins.1.max(skin));
        }
        let p = m.particles();
        let mut bits: Vec<u64> = Vec::new();
        for v in [&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz] {
            bits.extend(v.iter().map(|x| x.to_bits()));
        }
        bits.extend(m.fluid_velocity().iter().map(|x| x.to_bits()));
        (bits, skins, m.dem().list().builds)
    })
}

#[test]
fn an_adapted_skin_keeps_the_run_bit_identical_on_one_and_two_threads() {
    let s = scene();
    let d = s.particles.diameter;
    let (one, skins, builds) = run(&s, 1);
    let (two, skins_two, builds_two) = run(&s, 2);
    eprintln!("skins of the flow {:.3}-{:.3} d, {builds} builds", skins.0 / d, skins.1 / d);
    // the skin left its smallest value, and took the same values on both pools
    assert!(skins.1 > 2.0 * 0.02 * d, "skins {skins:?} (m)");
    assert_eq!((skins, builds), (skins_two, builds_two));
    let differing = one.iter().zip(&two).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "{differing} of {} values differ between 1 and 2 threads", one.len());
    assert_eq!(run(&s, 2).0, two);
}
