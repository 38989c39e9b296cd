//! Wall time of the Eulerian solver: Chassagne et al. 2023 case 1 (proposed model) from the
//! bed at rest to steady state, at the paper's resolution (120 cells, d/4) and at 400 cells.
//! Also the k-omega channel at Re_tau = 587.19 (cases/verification/channel_re590.toml, 120
//! stretched cells) to steady state, by the Eulerian solver and by `FluidColumn::solve_steady`.
//! Also the sheet-flow and dilute-suspension scenes (Revil-Baudard mobile bed, every closure
//! set; Cheng's dilute cases; the Rouse scene), each from its initial state to its steady
//! ending, which the bench asserts (docs/performance.md).
//! `cargo bench --bench eulerian`

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use saltus_core::scene::Scene;
use saltus_solvers::column::{Closures, ColumnParams, Coupling, FluidColumn, Grid, TopBoundary};
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{drive, Ending, Quiet};

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
                let ending = drive(&mut m, &mut Quiet).ending;
                assert_eq!(ending, Ending::Steady);
                m.steps()
            })
        });
    }
    group.finish();
}

fn channel_k_omega(c: &mut Criterion) {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/verification/channel_re590.toml");
    let scene = Scene::from_file_with(&file, &[]).expect("channel_re590");
    let cfg = Config::from_scene(&scene).expect("config");
    let mut group = c.benchmark_group("k_omega_channel_re590_to_steady");
    group.sample_size(20);
    group.bench_function("eulerian_120_stretched", |b| {
        b.iter(|| {
            let mut m = Eulerian::new(&scene, cfg.clone()).expect("solver");
            assert_eq!(drive(&mut m, &mut Quiet).ending, Ending::Steady);
            m.steps()
        })
    });
    let d = &scene.domain;
    let grid = Grid::geometric(cfg.cells, d.water_depth, d.stretching).expect("grid");
    let params = ColumnParams {
        pressure_gradient: scene.physics.pressure_gradient,
        top: TopBoundary::Symmetry,
        ..ColumnParams::default()
    };
    let closures = Closures {
        viscosity: scene.closures.viscosity.as_deref().expect("viscosity"),
        turbulence: scene.closures.turbulence.as_deref().expect("turbulence"),
        wall_friction: None,
    };
    let zero = vec![0.0; cfg.cells];
    let coupling = Coupling { phi: &zero, beta: &zero, u_p: &zero };
    group.bench_function("fluid_column_120_stretched", |b| {
        b.iter(|| {
            let mut col = FluidColumn::new(grid.clone(), params).expect("column");
            col.solve_steady(&coupling, &closures, 1e-10, 5000).expect("steady").iterations
        })
    });
    group.finish();
}

fn sheet_flow_and_dilute(c: &mut Criterion) {
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
    let mut group = c.benchmark_group("sheet_flow_and_dilute_scenes");
    group.sample_size(10);
    for rel in [
        "revil_baudard2015/mobile_bed_kinetic_mixing_length.toml",
        "revil_baudard2015/mobile_bed_mu_i_mixing_length.toml",
        "revil_baudard2015/mobile_bed_kinetic_k_omega.toml",
        "revil_baudard2015/mobile_bed_mu_i_k_omega.toml",
        "revil_baudard2015/fixed_bed_k_omega.toml",
        "cheng/dilute_kiger_pan.toml",
        "cheng/dilute_muste_ns1.toml",
        "revil_baudard2015/sheet_flow_mu_i.toml",
        "revil_baudard2015/sheet_flow_k_omega_mu_i.toml",
        "revil_baudard2015/sheet_flow_k_omega_kinetic.toml",
        "verification/rouse_parabolic.toml",
    ] {
        let scene = Scene::from_file_with(root.join(rel), &[]).expect("scene");
        let cfg = Config::from_scene(&scene).expect("config");
        group.bench_function(rel, |b| {
            b.iter(|| {
                let mut m = Eulerian::new(&scene, cfg.clone()).expect("solver");
                let ending = drive(&mut m, &mut Quiet).ending;
                assert_eq!(ending, Ending::Steady, "{rel}");
                m.steps()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, case01, channel_k_omega, sheet_flow_and_dilute);
criterion_main!(benches);
