//! Batch evaluation of every closure family on a 200-point column (ns per point =
//! reported time / 200), through the batch methods the solvers call once per column
//! evaluation: C_D Re (Eulerian drag kernel) and C_D (DEM), the hindrance factor, the
//! viscosity ratio, the local rheology's face path (control numbers, then friction) and
//! cell path (packing inverse, then pressure), the kinetic coefficients with and without
//! saltation, the eddy viscosity and the fluctuation diffusivity. Models are built through
//! the scene machinery, so each batch is one virtual call, as in the solvers.

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use saltus_core::closure::Family;
use saltus_core::scene::closure_from_value;
use saltus_core::{
    ColumnView, DragLaw, EffectiveViscosity, FlowScales, Fluctuation, GranularStress, Hindrance, KineticCoefficients,
    LocalState, SaltationInput, Turbulence, TurbulencePoint,
};

const N: usize = 200;

fn model<T>(family: Family, text: &str) -> Box<T>
where
    T: ?Sized + saltus_core::Describe + saltus_core::runtime::FromRuntime,
    Box<T>: serde::de::DeserializeOwned,
{
    let t: toml::Table = text.parse().expect("bench model table");
    closure_from_value(toml::Value::Table(t), family, Path::new("bench"), "bench").expect("bench model")
}

/// z, dz, phi, re_p, du/dz of a bed-like column.
type Column = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

fn column() -> Column {
    let dz = 30.5 * 6e-3 / N as f64;
    let z: Vec<f64> = (0..N).map(|i| (i as f64 + 0.5) * dz).collect();
    // a bed-like tanh profile from 0.6 to 0
    let phi: Vec<f64> = z.iter().map(|&z| 0.3 * (1.0 - ((z - 0.08) / 0.01).tanh())).collect();
    let re: Vec<f64> = (0..N).map(|i| 0.1 * 1.05f64.powi(i as i32)).collect();
    let dudz: Vec<f64> = z.iter().map(|&z| 50.0 * (-(z - 0.1f64).powi(2) / 1e-3).exp() + 1.0).collect();
    (z, vec![dz; N], phi, re, dudz)
}

fn benches(c: &mut Criterion) {
    saltus_closures::link();
    let (z, dz, phi, re, dudz) = column();
    let mut out = vec![0.0; N];
    let mut g = c.benchmark_group("closure_batch_200");
    g.throughput(Throughput::Elements(N as u64));

    for name in ["stokes", "dallavalle", "schiller_naumann", "haider_levenspiel"] {
        let m: Box<dyn DragLaw> = model(Family::Drag, &format!("type = \"{name}\""));
        g.bench_function(format!("drag/{name}_cd_re"), |b| b.iter(|| m.cd_re_batch(black_box(&re), &mut out)));
        g.bench_function(format!("drag/{name}_cd"), |b| b.iter(|| m.cd_batch(black_box(&re), &mut out)));
    }
    for name in ["none", "richardson_zaki", "di_felice"] {
        let m: Box<dyn Hindrance> = model(Family::Hindrance, &format!("type = \"{name}\""));
        g.bench_function(format!("hindrance/{name}"), |b| b.iter(|| m.factor_batch(black_box(&phi), &re, &mut out)));
    }
    for name in ["clear_fluid", "einstein", "batchelor_green", "krieger_dougherty", "gibilaro", "fry2024"] {
        let m: Box<dyn EffectiveViscosity> = model(Family::Viscosity, &format!("type = \"{name}\""));
        g.bench_function(format!("viscosity/{name}"), |b| b.iter(|| m.ratio_batch(black_box(&phi), &mut out)));
    }
    let states: Vec<LocalState> = (0..N)
        .map(|i| LocalState {
            shear_rate: dudz[i],
            pressure: 1.0 + 100.0 * phi[i],
            diameter: 6e-3,
            particle_density: 2500.0,
            fluid_viscosity: 1e-3,
        })
        .collect();
    for name in ["mu_i", "mu_k"] {
        let m: Box<dyn GranularStress> = model(Family::Granular, &format!("type = \"{name}\""));
        let local = m.as_local().expect("local rheology");
        let (mut x, mut phi_out) = (vec![0.0; N], vec![0.0; N]);
        g.bench_function(format!("granular/{name}_faces"), |b| {
            b.iter(|| {
                local.control_number_batch(black_box(&states), &mut x);
                local.eval_batch(&x, &mut out, &mut phi_out)
            })
        });
        g.bench_function(format!("granular/{name}_cells"), |b| {
            b.iter(|| {
                local.control_of_packing_batch(black_box(&phi), &mut x);
                local.pressure_at_batch(&states, &x, &mut out)
            })
        });
    }
    let fc: Box<dyn GranularStress> = model(Family::Granular, "type = \"frictional_collisional\"");
    let kt = fc.as_kinetic().expect("kinetic");
    let mut coefs = vec![KineticCoefficients::default(); N];
    g.bench_function("granular/frictional_collisional_coefficients", |b| {
        b.iter(|| kt.coefficients_batch(black_box(&phi), None, &mut coefs))
    });
    let salt: Vec<SaltationInput> = (0..N)
        .map(|i| SaltationInput { sqrt_t: 0.05, k_drag: 1e3 + i as f64, particle_density: 2500.0, diameter: 6e-3 })
        .collect();
    g.bench_function("granular/frictional_collisional_with_saltation", |b| {
        b.iter(|| kt.coefficients_batch(black_box(&phi), Some(&salt), &mut coefs))
    });
    for form in ["prandtl", "li_sawamoto", "berzi_fraccarollo"] {
        let m: Box<dyn Turbulence> = model(Family::Turbulence, &format!("type = \"mixing_length\"\nform = \"{form}\""));
        let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 6e-3, nu_f: 1e-6, transported: &[] };
        g.bench_function(format!("turbulence/mixing_length_{form}"), |b| {
            b.iter(|| m.eddy_viscosity(black_box(&col), &mut out))
        });
    }
    let tps: Vec<TurbulencePoint> = (0..N)
        .map(|i| TurbulencePoint { k: 1e-3 * (1.0 + i as f64), omega: 10.0, nu_t: 1e-4, reynolds_stress: 1e-3 })
        .collect();
    let scales = FlowScales { depth: 0.1, bulk_velocity: 1.0 };
    for name in ["none", "drw", "eim"] {
        let m: Box<dyn Fluctuation> = model(Family::Fluctuation, &format!("type = \"{name}\""));
        g.bench_function(format!("fluctuation/{name}_diffusivity"), |b| {
            b.iter(|| m.diffusivity_batch(black_box(&tps), &scales, &mut out))
        });
    }
    g.finish();
}

criterion_group! {
    name = closure_benches;
    config = Criterion::default().sample_size(30).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = benches
}
criterion_main!(closure_benches);
