//! One coupled DEM step (drag, contacts, integration; the fluid column solved every fluid
//! period, amortised) on the bed of Chassagne et al. 2023 case 1 in a 20 d x 20 d cell:
//! 5730 mobile and 455 fixed spheres of 6 mm, 945 fluid cells. On one and two threads.
//! Group `dem_peer_step`: the peer DEM code's bedload example
//! (`cases/maurin2015/peer_bedload_1165.toml`, 1165 mobile spheres) at the peer's time
//! step, 0.22 contact times (on one and two threads), and at the default 0.05, after 2 s
//! of flow.
//! `cargo bench --bench dem_step`

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::Stepper;

fn coupled_step(c: &mut Criterion) {
    saltus_closures::link();
    // case 1 in the DEM, as in compare_case01_solvers.toml
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/chassagne2023/case01.toml");
    let sets = [
        "solver.type=lagrangian",
        "closures.turbulence={type=\"mixing_length\", form=\"li_sawamoto\", phi_max=0.61}",
        "solver.lagrangian.settle_time=0.4",
        "solver.lagrangian.end_time=1e9",
    ]
    .map(String::from);
    let scene = Scene::from_file_with(&file, &sets).expect("case01 in the DEM");
    let mut group = c.benchmark_group("dem_coupled_step");
    group.sample_size(30);
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        let cfg = Config::from_scene(&scene).expect("config");
        let mut m = Lagrangian::new(&scene, cfg).expect("solver");
        pool.install(|| {
            m.deposit().expect("deposition");
            // let the flow start so that the bed moves and contacts change
            for _ in 0..50 {
                assert!(m.step_unit().is_none());
            }
        });
        group.throughput(Throughput::Elements(m.mobile() as u64));
        group.bench_function(format!("{}_particles_{threads}_threads", m.mobile()), |b| {
            b.iter(|| pool.install(|| m.step_dem().expect("step")))
        });
    }
    group.finish();
}

fn peer_step(c: &mut Criterion) {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/maurin2015/peer_bedload_1165.toml");
    let mut group = c.benchmark_group("dem_peer_step");
    group.sample_size(20);
    // two threads at the peer's step: the same state as one thread's (the run is
    // bit-identical on any thread count), so the two members compare like with like
    for (dt_safety, threads) in [("0.22", 1usize), ("0.22", 2), ("0.05", 1)] {
        let sets = [format!("solver.lagrangian.dt_safety={dt_safety}"), "solver.lagrangian.end_time=1e9".into()];
        let scene = Scene::from_file_with(&file, &sets).expect("the peer's case");
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        let mut m = Lagrangian::new(&scene, Config::from_scene(&scene).expect("config")).expect("solver");
        pool.install(|| {
            m.deposit().expect("deposition");
            // the flow accelerates from rest: after 2 s the grains saltate (qs* about 0.03,
            // the neighbour list rebuilt every few steps at 0.22)
            while m.time() < 2.0 {
                assert!(m.step_unit().is_none());
            }
        });
        group.throughput(Throughput::Elements(m.mobile() as u64));
        let name = if threads == 1 { "1_thread".to_string() } else { format!("{threads}_threads") };
        group.bench_function(format!("dt_safety_{dt_safety}_{name}"), |b| {
            b.iter(|| pool.install(|| m.step_dem().expect("step")))
        });
    }
    group.finish();
}

criterion_group!(benches, coupled_step, peer_step);
criterion_main!(benches);
