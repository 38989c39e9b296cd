//! Wall time of the Eulerian solver: Chassagne et al. 2023 case 1 (proposed model) from the
//! bed at rest to steady state, at the paper's resolution (120 cells, d/4) and at 400 cells.
//! `cargo bench --bench eulerian`

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use saltus_core::scene::Scene;
use saltus_solvers::eulerian::{Config, Ending, Eulerian};

fn case01(c: &mut Criterion) {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/chassagne2023/case01.toml");
    let mut group = c.benchmark_group("eulerian_case01_to_steady");
    group.sample_size(20);
    for cells in [120usize, 400] {
        let scene = Scene::from_file_with(&file, &[format!("domain.cells={cells}")]).expect("case01");
        let cfg = Config::from_scene(&scene).expect("config");
        group.bench_function(format!("{cells}_cells"), |b| {
            b.iter(|| {
                let mut m = Eulerian::new(&scene, cfg.clone()).expect("solver");
                let ending = m.run(&mut |_| true);
                assert_eq!(ending, Ending::Steady);
                m.steps()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, case01);
criterion_main!(benches);
