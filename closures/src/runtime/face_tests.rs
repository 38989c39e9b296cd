//! The faces of the granular, turbulence and fluctuation families with laws written as
//! Rust closures over slices (what a Python function is to the adapters): each built-in
//! law written so is the built-in model, bit for bit, through the scene loader.

use std::path::Path;

use saltus_core::param::ParamRange;
use saltus_core::rng::stream;
use saltus_core::runtime::{self, BatchFunction, Control, RuntimeModel, Variate, KINETIC_PARAMS};
use saltus_core::scene::{closure_from_value, granular_from_value, Particles};
use saltus_core::{
    ColumnView, FlowScales, Fluctuation, FluctuationDraw, GranularStress, KineticCoefficients, KineticTheory,
    LocalRheology, LocalState, Needs, Param, ParticleSlip, SaltationInput, Turbulence, TurbulencePoint,
};

use super::*;
use crate::fluctuation::EddyInteraction;
use crate::granular::{FrictionalCollisional, MuI};
use crate::turbulence::MixingLength;

type Law = dyn Fn(&[f64], &[&[f64]], &mut [&mut [f64]]) -> Result<usize, String> + Send + Sync;

struct Function(Box<Law>);

impl BatchFunction for Function {
    fn evaluate(&self, params: &[f64], inputs: &[&[f64]], outputs: &mut [&mut [f64]]) -> Result<usize, String> {
        (self.0)(params, inputs, outputs)
    }
}

fn function(
    law: impl Fn(&[f64], &[&[f64]], &mut [&mut [f64]]) -> Result<usize, String> + Send + Sync + 'static,
) -> Arc<dyn BatchFunction> {
    Arc::new(Function(Box::new(law)))
}

fn register(family: Family, name: &'static str, params: Vec<Param>, f: Arc<dyn BatchFunction>, shape: Shape) {
    runtime::register(RuntimeModel {
        family,
        name,
        source: "a test",
        equation: "a test law",
        params,
        limits: Vec::new(),
        convention: saltus_core::DragReynolds::Interstitial,
        depends_on_reynolds: false,
        function: f,
        shape,
        build,
    })
    .unwrap();
}

fn table(text: &str) -> toml::Value {
    toml::Value::Table(text.parse().unwrap())
}

fn particles() -> Particles {
    toml::from_str("diameter = 6e-3\ndensity = 2500.0\nrestitution = 0.7\nfriction = 0.4").unwrap()
}

fn granular(name: &str) -> Box<dyn GranularStress> {
    granular_from_value(table(&format!("type = \"{name}\"")), &particles(), Path::new("s.toml"), "closures.granular")
        .unwrap()
}

/// mu(I) of the built-in `mu_i` at its default parameters, over slices.
fn mu_i_law(p: &[f64], x: &[&[f64]], out: &mut [&mut [f64]]) -> Result<usize, String> {
    let m = MuI { mu_s: p[0], mu_2: p[1], i0: p[2], phi_c: p[3], b: p[4] };
    let (mu, rest) = out.split_at_mut(1);
    for ((o, q), &i) in mu[0].iter_mut().zip(rest[0].iter_mut()).zip(x[0]) {
        *o = m.friction(i);
        *q = m.packing(i);
    }
    Ok(2)
}

fn mu_i_params() -> Vec<Param> {
    let d = MuI::default();
    ["mu_s", "mu_2", "i0", "phi_c", "b"]
        .into_iter()
        .zip([d.mu_s, d.mu_2, d.i0, d.phi_c, d.b])
        .map(|(n, v)| Param::new(n, v, ParamRange::any(), "-", n))
        .collect()
}

fn state(gamma: f64) -> LocalState {
    LocalState { shear_rate: gamma, pressure: 0.0, diameter: 6e-3, particle_density: 2500.0, fluid_viscosity: 1e-3 }
}

#[test]
fn a_local_rheology_is_the_built_in_mu_i_with_its_inverse_or_bisected() {
    let inverse = function(|p, x, out| {
        let m = MuI { mu_s: p[0], mu_2: p[1], i0: p[2], phi_c: p[3], b: p[4] };
        for (o, &phi) in out[0].iter_mut().zip(x[0]) {
            *o = m.control_of_packing(phi);
        }
        Ok(1)
    });
    let shape = |inverse| Shape::Local { control: Control::Inertial, inverse };
    register(Family::Granular, "rt_mu_i", mu_i_params(), function(mu_i_law), shape(Some(inverse)));
    register(Family::Granular, "rt_mu_i_bisected", mu_i_params(), function(mu_i_law), shape(None));
    let built_in = MuI::default();
    let (with, bisected) = (granular("rt_mu_i"), granular("rt_mu_i_bisected"));
    let (with, bisected) = (with.as_local().unwrap(), bisected.as_local().unwrap());
    let x: Vec<f64> = (0..60).map(|i| 1e-4 * 1.3f64.powi(i)).chain([0.0, f64::INFINITY]).collect();
    let (mut mu, mut phi) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    with.eval_batch(&x, &mut mu, &mut phi);
    for i in 0..x.len() {
        assert_eq!(mu[i].to_bits(), built_in.friction(x[i]).to_bits());
        assert_eq!(phi[i].to_bits(), built_in.packing(x[i]).to_bits());
    }
    let phis: Vec<f64> = (0..=70).map(|i| i as f64 * 0.01).chain([-0.1, f64::NAN]).collect();
    let (mut a, mut b) = (vec![0.0; phis.len()], vec![0.0; phis.len()]);
    with.control_of_packing_batch(&phis, &mut a);
    bisected.control_of_packing_batch(&phis, &mut b);
    let s = state(5.0);
    for (i, &p) in phis.iter().enumerate() {
        assert_eq!(a[i].to_bits(), built_in.control_of_packing(p).to_bits(), "phi = {p}");
        // the array bisection is the trait's scalar one (the built-in law has a closed form)
        crate::testing::assert_inverses_match_bisection(bisected, &s, &[0.05, 0.3, 0.55, 0.6]);
        if a[i].is_finite() && a[i] > 0.0 {
            assert!((b[i] - a[i]).abs() <= 1e-10 * a[i], "phi = {p}: {} vs {}", b[i], a[i]);
        } else {
            assert_eq!(a[i], b[i], "phi = {p}");
        }
        assert_eq!(with.pressure_at(&s, a[i]).to_bits(), built_in.pressure_at(&s, a[i]).to_bits());
    }
    for g in [0.0, 1.0, -3.0] {
        for p in [0.0, 10.0, 1e4] {
            let st = LocalState { pressure: p, ..state(g) };
            assert_eq!(with.control_number(&st).to_bits(), built_in.control_number(&st).to_bits());
        }
    }
}

#[test]
fn a_rheology_of_k_needs_alpha_and_grain_keywords_come_from_the_particles() {
    // the function returns the keywords it was given: d, rho_p, e, mu_p after alpha
    let echo = function(|p, x, out| {
        out[0].fill(p[1] * p[2]);
        out[1].fill(p[3] + p[4]);
        assert_eq!(x.len(), 1);
        Ok(2)
    });
    let shape = Shape::Local { control: Control::Combined, inverse: None };
    let m = |params| RuntimeModel {
        family: Family::Granular,
        name: "rt_mu_k",
        source: "",
        equation: "",
        params,
        limits: Vec::new(),
        convention: saltus_core::DragReynolds::Interstitial,
        depends_on_reynolds: true,
        function: echo.clone(),
        shape: shape.clone(),
        build,
    };
    let e = runtime::register(m(Vec::new())).unwrap_err();
    assert!(e.contains("`alpha`"), "{e}");
    runtime::register(m(vec![Param::new("alpha", 0.5, ParamRange::any(), "-", "alpha")])).unwrap();
    let g = granular("rt_mu_k");
    let l = g.as_local().unwrap();
    assert_eq!(l.control_name(), "k");
    // mu = d rho_p = 15, phi = e + mu_p = 1.1 with the [particles] of `particles()`
    assert_eq!(l.friction(0.1), 6e-3 * 2500.0);
    assert_eq!(l.packing(0.1), 0.7 + 0.4);
    // K = J + alpha I^2 and its pressure, the definitions of mu_k
    let s = LocalState { pressure: 20.0, ..state(4.0) };
    let k = l.control_number(&s);
    assert!((k - (s.viscous_number() + 0.5 * s.inertial_number().powi(2))).abs() <= 1e-15 * k);
    let p = l.pressure_at(&s, k);
    assert!((p - 20.0).abs() <= 1e-12 * 20.0, "{p}");
}

#[test]
fn a_kinetic_coefficient_set_is_the_built_in_frictional_collisional() {
    // the built-in closure's coefficients over slices, its saltation input included
    let law = function(|_, x, out| {
        let fc = FrictionalCollisional::default();
        for i in 0..x[0].len() {
            let salt = SaltationInput { sqrt_t: x[1][i], k_drag: x[2][i], particle_density: 2500.0, diameter: 6e-3 };
            let c = fc.coefficients(x[0][i], (x[2][i] > 0.0).then_some(&salt));
            for (o, v) in out.iter_mut().zip([c.g0, c.f1, c.f2, c.f3, c.f4, c.e_eff]) {
                o[i] = v;
            }
        }
        Ok(6)
    });
    let fc = FrictionalCollisional::default();
    let values = [fc.p0, fc.phi_rlp, fc.phi_max, fc.static_friction()];
    let params = KINETIC_PARAMS.iter().zip(values).map(|(n, v)| Param::new(*n, v, ParamRange::any(), "-", n)).collect();
    register(
        Family::Granular,
        "rt_kinetic",
        params,
        law,
        Shape::Kinetic { saltation: true, linear_drag_dissipation: false },
    );
    let g = granular("rt_kinetic");
    let kt = g.as_kinetic().unwrap();
    assert!(kt.saltation_enabled());
    let phi: Vec<f64> = (0..64).map(|i| i as f64 * 0.01).collect();
    let salt: Vec<SaltationInput> = phi
        .iter()
        .map(|&p| SaltationInput {
            sqrt_t: 0.05 + p,
            k_drag: 1e3 * (1.0 + p),
            particle_density: 2500.0,
            diameter: 6e-3,
        })
        .collect();
    for salt in [None, Some(&salt[..])] {
        let (mut a, mut b) = (vec![KineticCoefficients::default(); 64], vec![KineticCoefficients::default(); 64]);
        kt.coefficients_batch(&phi, salt, &mut a);
        fc.coefficients_batch(&phi, salt, &mut b);
        assert_eq!(a, b);
    }
    for &p in &[0.0, 0.3, 0.58, 0.6, 0.62] {
        // at run time, as the solver evaluates them: powi folded at compile time may round
        // otherwise
        let p = std::hint::black_box(p);
        assert_eq!(kt.elastic_pressure(p), fc.elastic_pressure(p));
        assert_eq!(kt.elastic_pressure_derivative(p), fc.elastic_pressure_derivative(p));
    }
    assert_eq!(kt.static_friction(), fc.static_friction());
    assert_eq!(kt.drag_dissipation_factor(0.4, 2.0), fc.drag_dissipation_factor(0.4, 2.0));
    assert_eq!(kt.phi_max(), fc.phi_max);
}

#[test]
fn a_kinetic_coefficient_set_without_its_elastic_parameters_or_with_them_crossed_is_refused() {
    let m = |params: Vec<Param>| RuntimeModel {
        family: Family::Granular,
        name: "rt_kinetic_bad",
        source: "",
        equation: "",
        params,
        limits: Vec::new(),
        convention: saltus_core::DragReynolds::Interstitial,
        depends_on_reynolds: true,
        function: function(|_, _, _| Ok(6)),
        shape: Shape::Kinetic { saltation: false, linear_drag_dissipation: true },
        build,
    };
    let e = runtime::register(m(Vec::new())).unwrap_err();
    assert!(e.contains("`p0`"), "{e}");
    let crossed = KINETIC_PARAMS
        .iter()
        .zip([0.05, 0.64, 0.635, 0.36])
        .map(|(n, v)| Param::new(*n, v, ParamRange::any(), "-", n))
        .collect();
    runtime::register(m(crossed)).unwrap();
    let e =
        granular_from_value(table("type = \"rt_kinetic_bad\""), &particles(), Path::new("s.toml"), "closures.granular")
            .unwrap_err()
            .to_string();
    assert!(e.contains("s.toml") && e.contains("closures.granular") && e.contains("phi_rlp"), "{e}");
}

#[test]
fn a_mixing_length_is_the_built_in_li_sawamoto_bit_for_bit() {
    let law = function(|p, x, out| {
        let m = MixingLength { kappa: p[0], phi_max: p[1], ..MixingLength::default() };
        // the keywords after the parameters: grain diameter and fluid viscosity
        let col = ColumnView { z: x[0], dz: x[1], phi: x[2], dudz: x[3], diameter: p[2], nu_f: p[3], transported: &[] };
        m.mixing_length(&col, out[0]);
        Ok(1)
    });
    let params = vec![
        Param::new("kappa", 0.41, ParamRange::any(), "-", "von Karman"),
        Param::new("phi_max", 0.635, ParamRange::any(), "-", "packing"),
    ];
    register(Family::Turbulence, "rt_mixing_length", params, law, Shape::MixingLength);
    let t: Box<dyn Turbulence> = closure_from_value(
        table("type = \"rt_mixing_length\"\nphi_max = 0.6125"),
        Family::Turbulence,
        Path::new("s.toml"),
        "closures.turbulence",
    )
    .unwrap();
    let built_in = MixingLength { phi_max: 0.6125, ..MixingLength::default() };
    let n = 120;
    let dz = vec![1.5e-3; n];
    let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * 1.5e-3).collect();
    let phi: Vec<f64> = z.iter().map(|&z| 0.6125 * 0.5 * (1.0 - ((z - 0.075) / 0.005).tanh())).collect();
    let dudz: Vec<f64> = z.iter().map(|&z| 30.0 * (-z / 0.05).exp()).collect();
    let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 6e-3, nu_f: 1e-6, transported: &[] };
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    t.eddy_viscosity(&col, &mut a);
    built_in.eddy_viscosity(&col, &mut b);
    assert_eq!(a, b);
    assert!(t.provides().contains(saltus_core::Field::ReynoldsStress));
    // kappa z next to a clear-fluid wall
    let clear = vec![0.0; n];
    t.mixing_length(&ColumnView { phi: &clear, ..col }, &mut a);
    assert_eq!(a[0], 0.41 * z[0]);
}

/// The eddy interaction model as a law over arrays: the built-in draw with the
/// handed-in variates (three normals, one exponential) in place of its own stream.
fn eim_law(_: &[f64], x: &[&[f64]], out: &mut [&mut [f64]]) -> Result<usize, String> {
    let m = EddyInteraction::default();
    for i in 0..x[0].len() {
        // the built-in draw with the handed-in variates in place of its own stream
        let e = x[9][i];
        let (ux, uy, uz, dur) = match m.lagrangian_time(x[1][i]) {
            None => (0.0, 0.0, 0.0, f64::INFINITY),
            Some(tl) => {
                let t_e = m.c0 * tl * e;
                if !(x[0][i].is_finite() && x[0][i] > 0.0) {
                    (0.0, 0.0, 0.0, t_e)
                } else {
                    let s = (2.0 * x[0][i] / 3.0).sqrt();
                    let p = ParticleSlip { slip: x[4][i], response_time: x[5][i] };
                    let d = EddyInteraction::crossing_time(t_e * s, &p).map_or(t_e, |t_c| t_c.min(t_e));
                    (s * x[6][i], s * x[7][i], s * x[8][i], d)
                }
            }
        };
        out[0][i] = ux;
        out[1][i] = uy;
        out[2][i] = uz;
        out[3][i] = dur;
    }
    Ok(4)
}

#[test]
fn a_particle_draw_with_the_eim_variates_is_the_built_in_eim() {
    let eim = EddyInteraction::default();
    let draw = function(eim_law);
    let diffusivity = function(|_, x, out| {
        let eim = EddyInteraction::default();
        for (i, o) in out[0].iter_mut().enumerate() {
            let t = TurbulencePoint { k: x[0][i], omega: x[1][i], nu_t: x[2][i], reynolds_stress: x[3][i] };
            *o = eim.diffusivity(&t, &FlowScales::default());
        }
        Ok(1)
    });
    let variates = vec![Variate::Normal, Variate::Normal, Variate::Normal, Variate::Exponential];
    let needs = Needs::of(&[saltus_core::Field::Tke, saltus_core::Field::Omega]);
    register(Family::Fluctuation, "rt_eim", Vec::new(), draw, Shape::Fluctuation { diffusivity, variates, needs });
    let f: Box<dyn Fluctuation> = closure_from_value(
        table("type = \"rt_eim\""),
        Family::Fluctuation,
        Path::new("s.toml"),
        "closures.fluctuation",
    )
    .unwrap();
    assert_eq!(f.needs(), needs);
    let s = FlowScales { depth: 0.1, bulk_velocity: 1.0 };
    let points: Vec<TurbulencePoint> = (0..40)
        .map(|i| TurbulencePoint { k: 1e-3 * i as f64, omega: 0.5 * i as f64, nu_t: 0.0, reynolds_stress: 0.0 })
        .collect();
    for (i, t) in points.iter().enumerate() {
        let p = ParticleSlip { slip: 0.01 * i as f64, response_time: 0.1 };
        // the same stream, then the next number of it (the DEM's random phase): the
        // adapter took exactly the variates the built-in model takes
        let (mut r1, mut r2) = (stream(11, i as u64), stream(11, i as u64));
        assert_eq!(f.draw(t, &p, &s, &mut r1), eim.draw(t, &p, &s, &mut r2), "point {i}");
        assert_eq!(rand::Rng::gen::<u64>(&mut r1), rand::Rng::gen::<u64>(&mut r2));
    }
    let (mut a, mut b) = (vec![0.0; 40], vec![0.0; 40]);
    f.diffusivity_batch(&points, &s, &mut a);
    eim.diffusivity_batch(&points, &s, &mut b);
    assert_eq!(a, b);
    assert!(a.iter().all(|&d| d >= 0.0));
}

#[test]
fn a_chunk_of_draws_is_one_call_and_the_draws_of_one_call_per_particle_on_any_thread_count() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let draw = function(|p, x, out| {
        CALLS.fetch_add(1, Ordering::Relaxed);
        eim_law(p, x, out)
    });
    let diffusivity = function(|_, _, out| {
        out[0].fill(0.0);
        Ok(1)
    });
    let variates = vec![Variate::Normal, Variate::Normal, Variate::Normal, Variate::Exponential];
    let shape = Shape::Fluctuation { diffusivity, variates, needs: Needs::NONE };
    register(Family::Fluctuation, "rt_eim_chunked", Vec::new(), draw, shape);
    let f: Box<dyn Fluctuation> = closure_from_value(
        table("type = \"rt_eim_chunked\""),
        Family::Fluctuation,
        Path::new("s.toml"),
        "closures.fluctuation",
    )
    .unwrap();
    let eim = EddyInteraction::default();
    let s = FlowScales { depth: 0.1, bulk_velocity: 1.0 };
    let n = 300;
    let t: Vec<TurbulencePoint> = (0..n)
        .map(|i| TurbulencePoint { k: 1e-4 * (i % 17) as f64, omega: 0.3 * (i % 23) as f64, ..Default::default() })
        .collect();
    let p: Vec<ParticleSlip> =
        (0..n).map(|i| ParticleSlip { slip: 1e-3 * (i % 11) as f64, response_time: 0.05 }).collect();
    let streams = || (0..n as u64).map(|i| stream(5, 1000 + i)).collect::<Vec<_>>();
    // one chunk, one call
    let mut one = streams();
    let mut batch = vec![FluctuationDraw::default(); n];
    let before = CALLS.load(Ordering::Relaxed);
    f.draw_batch(&t, &p, &s, &mut one.iter_mut().collect::<Vec<_>>(), &mut batch);
    assert_eq!(CALLS.load(Ordering::Relaxed) - before, 1);
    // two threads, a chunk each
    let mut two = streams();
    let mut split = vec![FluctuationDraw::default(); n];
    let h = n / 2 + 7;
    let ((ta, tb), (pa, pb)) = (t.split_at(h), p.split_at(h));
    let (ra, rb) = two.split_at_mut(h);
    let (oa, ob) = split.split_at_mut(h);
    std::thread::scope(|scope| {
        let f = &f;
        scope.spawn(move || f.draw_batch(ta, pa, &s, &mut ra.iter_mut().collect::<Vec<_>>(), oa));
        scope.spawn(move || f.draw_batch(tb, pb, &s, &mut rb.iter_mut().collect::<Vec<_>>(), ob));
    });
    assert_eq!(batch, split);
    // the built-in model, one draw per particle, from the same streams: the same draws,
    // and every stream left at the same number (the DEM's random phase comes next)
    let mut own = streams();
    for i in 0..n {
        assert_eq!(batch[i], eim.draw(&t[i], &p[i], &s, &mut own[i]), "particle {i}");
        let next = |r: &mut saltus_core::rng::Rng| rand::Rng::gen::<u64>(r);
        let (a, b, c) = (next(&mut one[i]), next(&mut two[i]), next(&mut own[i]));
        assert!(a == c && b == c, "particle {i}");
    }
}
