//! One coupled DEM step (drag, contacts, integration; the fluid column solved every fluid
//! period, amortised) on the bed of Chassagne et al. 2023 case 1 in a 20 d x 20 d cell:
//! 5730 mobile and 455 fixed spheres of 6 mm, 945 fluid cells. On one and two threads.
//! Group `dem_peer_step`: the peer DEM code's bedload example
//! (`cases/maurin2015/peer_bedload_1165.toml`, 1165 mobile spheres) at the peer's time
//! step, 0.22 contact times (on one and two threads), and at the default 0.05, after 2 s
//! of flow.
//!
//! Every member times the same stretch of flow: the state after the spin-up is saved,
//! and each measurement restores it and steps through [`STRETCH`] seconds of flow (the
//! restore not timed), as many times as criterion asks for steps. Stepping one model on
//! through criterion's warm-up and samples instead would time another stretch of a flow
//! that is still accelerating for each member, one that depends on how fast the member
//! is (criterion doubles its warm-up iterations until 3 s have passed). The steps of a
//! stretch run inside one `install` of the pool, as a run's fluid period does, so that a
//! handoff from the calling thread into the pool is not timed for every step.
//! `cargo bench --bench dem_step`

use std::path::Path;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::Stepper;

/// Seconds of flow each measurement steps through from the saved state.
const STRETCH: f64 = 0.05;

/// Time `iters` DEM steps of `m`, in stretches of [`STRETCH`] s of flow from `state`.
fn stretches(m: &mut Lagrangian, state: &[u8], pool: &rayon::ThreadPool, iters: u64) -> Duration {
    let per_stretch = ((STRETCH / m.dt()).ceil() as u64).max(1);
    let mut total = Duration::ZERO;
    let mut done = 0;
    while done < iters {
        m.restore(state).expect("the saved state restores");
        let n = per_stretch.min(iters - done);
        let start = Instant::now();
        pool.install(|| {
            for _ in 0..n {
                m.step_dem().expect("step");
            }
        });
        total += start.elapsed();
        done += n;
    }
    total
}

/// Bench `m` from its present state as `name` of `group`.
fn bench_from_here(
    group: &mut BenchmarkGroup<criterion::measurement::WallTime>,
    name: String,
    m: &mut Lagrangian,
    pool: &rayon::ThreadPool,
) {
    let mut state = Vec::new();
    m.save(&mut state).expect("the state saves");
    group.throughput(Throughput::Elements(m.mobile() as u64));
    group.bench_function(name, |b| b.iter_custom(|iters| stretches(m, &state, pool, iters)));
}

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
        let name = format!("{}_particles_{threads}_threads", m.mobile());
        bench_from_here(&mut group, name, &mut m, &pool);
    }
    group.finish();
}

fn peer_step(c: &mut Criterion) {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/maurin2015/peer_bedload_1165.toml");
    let mut group = c.benchmark_group("dem_peer_step");
    group.sample_size(20);
    // two threads at the peer's step from the same state as one thread's (the run is
    // bit-identical on any thread count), through the same stretch of flow
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
        let name = if threads == 1 { "1_thread".to_string() } else { format!("{threads}_threads") };
        bench_from_here(&mut group, format!("dt_safety_{dt_safety}_{name}"), &mut m, &pool);
    }
    group.finish();
}

criterion_group!(benches, coupled_step, peer_step);
criterion_main!(benches);
