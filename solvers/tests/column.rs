//! Verification of the 1D column fluid solver (docs/verification.md, benchmarks 1 and 2, drag
//! coupling, bed case, error paths). Run with `cargo test -p saltus-solvers --release`.

mod common;
use common::{turbulence, viscosity};

use std::path::Path;

use approx::assert_relative_eq;
use saltus_solvers::column::{Closures, ColumnError, ColumnParams, Coupling, FluidColumn, Grid, TopBoundary};

struct Inputs {
    phi: Vec<f64>,
    beta: Vec<f64>,
    u_p: Vec<f64>,
}

impl Inputs {
    fn clear(n: usize) -> Self {
        Self { phi: vec![0.0; n], beta: vec![0.0; n], u_p: vec![0.0; n] }
    }
    fn coupling(&self) -> Coupling<'_> {
        Coupling { phi: &self.phi, beta: &self.beta, u_p: &self.u_p }
    }
}

/// |wall stress - integral of (S - beta (u - u_p)) dz| and the scale sum (|S| + |drag|) dz.
fn integral_balance(col: &FluidColumn, inp: &Inputs) -> (f64, f64) {
    let dz = col.grid().dz();
    let (mut sum, mut scale) = (0.0, 0.0);
    for (i, &dzi) in dz.iter().enumerate() {
        let s = col.driving()[i] * dzi;
        let d = inp.beta[i] * (col.velocity()[i] - inp.u_p[i]) * dzi;
        sum += s - d;
        scale += s.abs() + d.abs();
    }
    let top = col.shear_stress()[dz.len()];
    ((col.wall_shear_stress() - top - sum).abs(), scale)
}

#[test]
fn laminar_couette_is_exact_at_centres_and_faces() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let (h, lid) = (0.02, 0.3);
    for grid in [Grid::uniform(50, h).unwrap(), Grid::geometric(64, h, 1.05).unwrap()] {
        let params = ColumnParams { top: TopBoundary::Lid { velocity: lid }, ..ColumnParams::default() };
        let mut col = FluidColumn::new(grid, params).unwrap();
        let inp = Inputs::clear(col.grid().len());
        let rep = col.solve_steady(&inp.coupling(), &closures, 1e-12, 10).unwrap();
        assert!(rep.iterations <= 2, "{rep:?}");
        let mut worst: f64 = 0.0;
        for (u, z) in col.velocity().iter().zip(col.grid().centres()) {
            worst = worst.max((u - lid * z / h).abs() / lid);
        }
        for (u, z) in col.face_velocity().iter().zip(col.grid().faces()) {
            worst = worst.max((u - lid * z / h).abs() / lid);
        }
        println!("couette: max relative error {worst:.2e}");
        assert!(worst < 1e-10);
        let tau = 1000.0 * 1e-6 * lid / h;
        for s in col.shear_stress() {
            assert_relative_eq!(*s, tau, max_relative = 1e-10);
        }
    }
}

#[test]
fn two_layer_couette_harmonic_faces_are_exact() {
    // phi = 0.6 below h/2 (a face), 0 above: eps nu_eff / nu_f = 0.4 * 2.5 = 1 with Einstein
    // (control), 0.4 * 206 = 82 with Krieger-Dougherty. The stress is uniform and u
    // piecewise linear, which the distance-weighted harmonic face mean reproduces exactly
    // at the centres and the flux-continuity interpolation at the interface face
    let lam = turbulence("type = \"laminar\"");
    for law in ["einstein", "krieger_dougherty"] {
        let visc = viscosity(&format!("type = \"{law}\""));
        let closures = Closures { viscosity: visc.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
        let (h, n, lid, phi_bed) = (0.02, 40, 0.3, 0.6);
        let params = ColumnParams { top: TopBoundary::Lid { velocity: lid }, ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
        let mut inp = Inputs::clear(n);
        for p in &mut inp.phi[..n / 2] {
            *p = phi_bed;
        }
        col.solve_steady(&inp.coupling(), &closures, 1e-12, 10).unwrap();
        let k_bed = (1.0 - phi_bed) * 1e-6 * visc.ratio(phi_bed);
        let k_top = 1e-6;
        // tau = rho U / (h/2 / k_bed + h/2 / k_top)
        let tau = 1000.0 * lid / (0.5 * h / k_bed + 0.5 * h / k_top);
        let exact = |z: f64| {
            if z <= 0.5 * h {
                tau / (1000.0 * k_bed) * z
            } else {
                lid - tau / (1000.0 * k_top) * (h - z)
            }
        };
        let mut worst: f64 = 0.0;
        for (u, &z) in col.velocity().iter().zip(col.grid().centres()) {
            worst = worst.max((u - exact(z)).abs() / lid);
        }
        println!("two-layer Couette ({law}, k jump {:.3}): max error {worst:.2e}", k_top / k_bed);
        assert!(worst < 1e-10);
        assert_relative_eq!(col.wall_shear_stress(), tau, max_relative = 1e-10);
        assert_relative_eq!(col.face_velocity()[n / 2], exact(0.5 * h), max_relative = 1e-10);
    }
}

#[test]
fn laminar_open_channel_is_exact_at_nodes() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let (h, n) = (0.01, 40);
    let mu = 1000.0 * 1e-6;
    // driven by a pressure gradient, then by gravity along a slope (same G), then with a
    // symmetry plane on top
    let cases = [
        (2.0, 0.0, TopBoundary::FreeSurface),
        (0.0, 2.0 / 1000.0, TopBoundary::FreeSurface),
        (2.0, 0.0, TopBoundary::Symmetry),
    ];
    for (gx_p, g_sin, top) in cases {
        let g = gx_p + 1000.0 * g_sin;
        let params = ColumnParams { pressure_gradient: gx_p, gravity_x: g_sin, top, ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
        let inp = Inputs::clear(n);
        col.solve_steady(&inp.coupling(), &closures, 1e-12, 10).unwrap();
        let exact = |z: f64| g / (2.0 * mu) * (2.0 * h * z - z * z);
        let umax = exact(h);
        let mut worst: f64 = 0.0;
        for (u, &z) in col.velocity().iter().zip(col.grid().centres()) {
            worst = worst.max((u - exact(z)).abs() / umax);
        }
        println!("open channel: centres max relative error {worst:.2e}, wall shear {}", col.wall_shear_stress());
        assert!(worst < 1e-10);
        assert_relative_eq!(col.wall_shear_stress(), g * h, max_relative = 1e-10);
        // walls exact; interior faces linear interpolation of a parabola: error G dz^2/(8 mu)
        let f = col.face_velocity();
        assert_eq!(f[0], 0.0);
        assert_relative_eq!(f[n], umax, max_relative = 1e-10);
        let dz = h / n as f64;
        for (u, &z) in f.iter().zip(col.grid().faces()).take(n).skip(1) {
            assert_relative_eq!(exact(z) - u, g * dz * dz / (8.0 * mu), max_relative = 1e-6);
        }
        // stress linear: tau = G (h - z)
        for (s, &z) in col.shear_stress().iter().zip(col.grid().faces()) {
            assert!((s - g * (h - z)).abs() <= 1e-10 * g * h);
        }
    }
}

#[test]
fn laminar_open_channel_stretched_grid_is_second_order() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let (h, g, mu) = (0.01, 2.0, 1e-3);
    let mut errors = Vec::new();
    for n in [40usize, 80, 160] {
        // same stretching law at every resolution: total growth 8 from the wall to the top
        let ratio = 8f64.powf(1.0 / (n - 1) as f64);
        let params = ColumnParams { pressure_gradient: g, ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::geometric(n, h, ratio).unwrap(), params).unwrap();
        let inp = Inputs::clear(n);
        col.solve_steady(&inp.coupling(), &closures, 1e-12, 10).unwrap();
        let exact = |z: f64| g / (2.0 * mu) * (2.0 * h * z - z * z);
        let e = col
            .velocity()
            .iter()
            .zip(col.grid().centres())
            .map(|(u, &z)| (u - exact(z)).abs() / exact(h))
            .fold(0.0, f64::max);
        assert_relative_eq!(col.wall_shear_stress(), g * h, max_relative = 1e-10);
        errors.push(e);
    }
    println!("stretched open channel errors {errors:?}");
    for w in errors.windows(2) {
        assert!(w[0] / w[1] > 3.5, "order < 2: {errors:?}");
    }
}

/// u+ of the mixing-length model with viscosity, u+' = 2 tau+ / (1 + sqrt(1 + 4 (kappa z+)^2 tau+)),
/// tau+ = 1 - z/h, integrated by Simpson's rule at each of the points `zp` (increasing).
fn reference_profile(zp: &[f64], h_plus: f64, kappa: f64) -> Vec<f64> {
    let dudz = |z: f64| {
        let t = 1.0 - z / h_plus;
        2.0 * t / (1.0 + (1.0 + 4.0 * (kappa * z).powi(2) * t).sqrt())
    };
    let mut out = Vec::with_capacity(zp.len());
    let (mut z0, mut u) = (0.0, 0.0);
    for &z1 in zp {
        let m = 64;
        let step = (z1 - z0) / m as f64;
        let mut s = dudz(z0) + dudz(z1);
        for k in 1..m {
            s += dudz(z0 + k as f64 * step) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        u += s * step / 3.0;
        out.push(u);
        z0 = z1;
    }
    out
}

#[test]
fn turbulent_log_layer_with_prandtl_mixing_length() {
    let kappa = 0.41;
    let prandtl = turbulence("type = \"mixing_length\"\nform = \"prandtl\"\nkappa = 0.41");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: prandtl.as_ref(), wall_friction: None };
    let (rho, nu, h) = (1000.0, 1e-6, 0.1);
    for (h_plus, n, ratio, slope_tol) in [(1.0e5, 400, 1.03, 0.02), (5.0e3, 300, 1.02, 0.04)] {
        let u_star = h_plus * nu / h;
        let params = ColumnParams { pressure_gradient: rho * u_star * u_star / h, ..ColumnParams::default() };
        let grid = Grid::geometric(n, h, ratio).unwrap();
        assert!(grid.dz()[0] * u_star / nu < 1.0);
        let mut col = FluidColumn::new(grid, params).unwrap();
        let inp = Inputs::clear(n);
        let t0 = std::time::Instant::now();
        let rep = col.solve_steady(&inp.coupling(), &closures, 1e-12, 500).unwrap();
        let elapsed = t0.elapsed();
        // total stress linear: rho u*^2 (1 - z/h) at every face
        let tau_w = rho * u_star * u_star;
        let stress_err = col
            .shear_stress()
            .iter()
            .zip(col.grid().faces())
            .map(|(s, &z)| (s - tau_w * (1.0 - z / h)).abs() / tau_w)
            .fold(0.0, f64::max);
        assert!(stress_err < 1e-6, "total stress not linear: {stress_err:e}");
        // slope of u+ against ln z+ (least squares) in 30 < z+ < 0.2 h+
        let zp: Vec<f64> = col.grid().centres().iter().map(|z| z * u_star / nu).collect();
        let up: Vec<f64> = col.velocity().iter().map(|u| u / u_star).collect();
        let pts: Vec<(f64, f64)> =
            zp.iter().zip(&up).filter(|(z, _)| **z > 30.0 && **z < 0.2 * h_plus).map(|(z, u)| (z.ln(), *u)).collect();
        let m = pts.len() as f64;
        let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / m, pts.iter().map(|p| p.1).sum::<f64>() / m);
        let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        // the model equation solved exactly (quadrature) at the same points
        let reference = reference_profile(&zp, h_plus, kappa);
        let ref_pts: Vec<(f64, f64)> = zp
            .iter()
            .zip(&reference)
            .filter(|(z, _)| **z > 30.0 && **z < 0.2 * h_plus)
            .map(|(z, u)| (z.ln(), *u))
            .collect();
        let rmy = ref_pts.iter().map(|p| p.1).sum::<f64>() / m;
        let ref_slope = ref_pts.iter().map(|p| (p.0 - mx) * (p.1 - rmy)).sum::<f64>()
            / ref_pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        let profile_err = up
            .iter()
            .zip(&reference)
            .zip(&zp)
            .filter(|(_, z)| **z > 1.0)
            .map(|((u, r), _)| (u - r).abs() / r)
            .fold(0.0, f64::max);
        println!(
            "log layer h+ = {h_plus}: {} iterations, residual {:.1e}, {:.1} ms, kappa * slope = {:.4} \
             (model exact {:.4}), max |u+ - u+_ref|/u+_ref (z+ > 1) = {profile_err:.2e}, stress error {stress_err:.1e}, \
             u+(centre) = {:.2}",
            rep.iterations,
            rep.residual,
            elapsed.as_secs_f64() * 1e3,
            slope * kappa,
            ref_slope * kappa,
            up[n - 1]
        );
        assert!((slope * kappa - 1.0).abs() < slope_tol, "kappa * slope = {}", slope * kappa);
        assert!(profile_err < 5e-3);
    }
}

#[test]
fn drag_coupling_interior_balance_and_integral_balance() {
    let lam = turbulence("type = \"laminar\"");
    let einstein = viscosity("type = \"einstein\"");
    let closures = Closures { viscosity: einstein.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let (h, n, phi, beta, up) = (0.01, 400, 0.3, 1.0e5, 0.05);
    let params = ColumnParams { gravity_x: 9.81 * 0.05, pressure_gradient: 30.0, ..ColumnParams::default() };
    let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
    let inp = Inputs { phi: vec![phi; n], beta: vec![beta; n], u_p: vec![up; n] };
    col.solve_steady(&inp.coupling(), &closures, 1e-12, 10).unwrap();
    let eps = 1.0 - phi;
    let s = eps * (1000.0 * 9.81 * 0.05 + 30.0);
    let u_eq = up + s / beta;
    // algebraic balance in the upper half (the wall layer has thickness
    // delta = sqrt(rho eps nu_eff / beta) = h / 90)
    let interior = col.velocity()[n / 2..].iter().map(|u| (u - u_eq).abs() / u_eq).fold(0.0, f64::max);
    // analytic profile u_eq (1 - cosh((h - z)/delta) / cosh(h/delta))
    let k = eps * 1e-6 * (1.0 + 2.5 * phi);
    let delta = (1000.0 * k / beta).sqrt();
    let profile = col
        .velocity()
        .iter()
        .zip(col.grid().centres())
        .map(|(u, &z)| (u - u_eq * (1.0 - ((h - z) / delta).cosh() / (h / delta).cosh())).abs() / u_eq)
        .fold(0.0, f64::max);
    let (imbalance, scale) = integral_balance(&col, &inp);
    println!(
        "drag: interior error {interior:.2e}, profile error {profile:.2e} (delta/dz = {:.1}), integral imbalance \
         {:.2e} of the wall stress {:.4e} Pa ({:.2e} of the budget)",
        delta / (h / n as f64),
        imbalance / col.wall_shear_stress().abs(),
        col.wall_shear_stress(),
        imbalance / scale
    );
    assert!(interior < 1e-10);
    assert!(profile < 1e-2);
    assert!(imbalance < 1e-10 * col.wall_shear_stress().abs());
}

#[test]
fn li_sawamoto_bed_case() {
    let ls = turbulence("type = \"mixing_length\"\nform = \"li_sawamoto\"");
    let kd = viscosity("type = \"krieger_dougherty\"");
    let closures = Closures { viscosity: kd.as_ref(), turbulence: ls.as_ref(), wall_friction: None };
    let (h, n, zb) = (0.1, 300, 0.03);
    let params = ColumnParams { gravity_x: 9.81 * 0.01, diameter: 6e-3, ..ColumnParams::default() };
    let grid = Grid::uniform(n, h).unwrap();
    let inp = {
        let bed: Vec<bool> = grid.centres().iter().map(|&z| z < zb).collect();
        Inputs {
            phi: bed.iter().map(|&b| if b { 0.6 } else { 0.0 }).collect(),
            beta: bed.iter().map(|&b| if b { 1.0e6 } else { 0.0 }).collect(),
            u_p: vec![0.0; n],
        }
    };
    let mut col = FluidColumn::new(grid, params).unwrap();
    let t0 = std::time::Instant::now();
    let rep = col.solve_steady(&inp.coupling(), &closures, 1e-13, 1000).unwrap();
    let elapsed = t0.elapsed();
    let u = col.velocity();
    assert!(u.iter().all(|v| v.is_finite()));
    let umax = u.iter().cloned().fold(0.0, f64::max);
    // 30 drag penetration lengths sqrt(rho eps nu_eff / beta) ~ 0.3 mm into the bed, the velocity is the algebraic balance eps rho g S / beta (~4e-5 m/s)
    let deep = zb - 0.01;
    let in_bed =
        u.iter().zip(col.grid().centres()).filter(|(_, &z)| z < deep).map(|(v, _)| v.abs()).fold(0.0, f64::max);
    let algebraic = 0.4 * 1000.0 * 9.81 * 0.01 / 1.0e6;
    let deep_err = u
        .iter()
        .zip(col.grid().centres())
        .filter(|(_, &z)| z < deep && z > 0.005)
        .map(|(v, _)| (v - algebraic).abs() / algebraic)
        .fold(0.0, f64::max);
    let (imbalance, scale) = integral_balance(&col, &inp);
    // above the bed the stress is the weight of the fluid above: rho g S (h - z)
    let nb = (zb / (h / n as f64)).round() as usize;
    let stress_above = col.shear_stress()[nb..]
        .iter()
        .zip(&col.grid().faces()[nb..])
        .map(|(s, &z)| (s - 1000.0 * 9.81 * 0.01 * (h - z)).abs())
        .fold(0.0, f64::max)
        / (1000.0 * 9.81 * 0.01 * (h - zb));
    println!(
        "bed: {} iterations in {:.1} ms, residual {:.1e}, u max {umax:.4} m/s, max |u| deeper than 10 mm in the bed {in_bed:.2e}, (deep bed vs algebraic {deep_err:.1e}) \
         depth average {:.4} m/s, integral imbalance {:.2e} of the budget, stress above bed error {stress_above:.1e}",
        rep.iterations,
        elapsed.as_secs_f64() * 1e3,
        rep.residual,
        col.depth_averaged_velocity(),
        imbalance / scale
    );
    assert!(in_bed < 1e-3 * umax);
    assert!(deep_err < 1e-6);
    assert!(imbalance < 1e-10 * scale);
    assert!(stress_above < 1e-8);
    // monotone profile above the bed
    for w in u[nb..].windows(2) {
        assert!(w[1] >= w[0]);
    }
}

#[test]
fn backward_euler_steps_drag_relaxation_and_reach_steady_state() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let (h, n, phi, beta, up, dt) = (0.01, 100, 0.2, 1.0e5, 0.02, 1e-3);
    let params = ColumnParams { pressure_gradient: 50.0, ..ColumnParams::default() };
    let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
    let inp = Inputs { phi: vec![phi; n], beta: vec![beta; n], u_p: vec![up; n] };
    // far from the wall one step is the implicit drag relaxation
    // (eps rho / dt + beta) u1 = eps rho / dt u0 + eps G + beta u_p
    col.step(dt, &inp.coupling(), &closures).unwrap();
    let a = (1.0 - phi) * 1000.0 / dt;
    let u1 = ((1.0 - phi) * 50.0 + beta * up) / (a + beta);
    assert_relative_eq!(col.velocity()[n - 1], u1, max_relative = 1e-12);
    assert_relative_eq!(col.time(), dt);
    for _ in 0..2000 {
        col.step(dt, &inp.coupling(), &closures).unwrap();
    }
    let transient = col.velocity().to_vec();
    assert!(col.residual() < 1e-10, "residual {}", col.residual());
    col.solve_steady(&inp.coupling(), &closures, 1e-13, 10).unwrap();
    for (a, b) in transient.iter().zip(col.velocity()) {
        assert_relative_eq!(*a, *b, max_relative = 1e-9);
    }
    // the turbulent case stepped in time converges to the same state as solve_steady
    let prandtl = turbulence("type = \"mixing_length\"\nform = \"prandtl\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: prandtl.as_ref(), wall_friction: None };
    // h = 0.1 m, u* = 0.032 m/s (h+ = 3200)
    let params = ColumnParams { pressure_gradient: 10.0, ..ColumnParams::default() };
    let clear_in = Inputs::clear(n);
    let mut stepped = FluidColumn::new(Grid::geometric(n, 0.1, 1.06).unwrap(), params).unwrap();
    // turbulent diffusion time h^2 / max(nu_t) ~ 80 s
    for _ in 0..1500 {
        stepped.step(1.0, &clear_in.coupling(), &closures).unwrap();
    }
    println!("stepped turbulent column: t = {} s, residual {:.1e}", stepped.time(), stepped.residual());
    let mut steady = FluidColumn::new(Grid::geometric(n, 0.1, 1.06).unwrap(), params).unwrap();
    steady.solve_steady(&clear_in.coupling(), &closures, 1e-12, 500).unwrap();
    for (a, b) in stepped.velocity().iter().zip(steady.velocity()) {
        assert_relative_eq!(*a, *b, max_relative = 1e-6);
    }
}

#[test]
fn nan_in_beta_is_an_error_naming_cell_and_field() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let n = 20;
    let mut col = FluidColumn::new(Grid::uniform(n, 0.01).unwrap(), ColumnParams::default()).unwrap();
    let mut inp = Inputs::clear(n);
    inp.beta[7] = f64::NAN;
    let err = col.step(1e-3, &inp.coupling(), &closures).unwrap_err();
    assert!(matches!(err, ColumnError::InvalidInput { field: "beta", cell: 7, .. }), "{err:?}");
    let msg = err.to_string();
    println!("{msg}");
    assert!(msg.contains("beta") && msg.contains("cell 7"));
    let err = col.solve_steady(&inp.coupling(), &closures, 1e-10, 10).unwrap_err();
    assert!(matches!(err, ColumnError::InvalidInput { field: "beta", cell: 7, .. }));
    // wrong length and out-of-range phi
    let short = Inputs::clear(n - 1);
    assert!(matches!(
        col.step(1e-3, &short.coupling(), &closures),
        Err(ColumnError::Length { field: "phi", expected: 20, found: 19 })
    ));
    let mut inp = Inputs::clear(n);
    inp.phi[3] = 1.0;
    assert!(matches!(
        col.step(1e-3, &inp.coupling(), &closures),
        Err(ColumnError::InvalidInput { field: "phi", cell: 3, .. })
    ));
    // Krieger-Dougherty diverges above phi_m: refused with the cell
    let kd = viscosity("type = \"krieger_dougherty\"");
    let kd_closures = Closures { viscosity: kd.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    inp.phi[3] = 0.63;
    assert!(matches!(
        col.step(1e-3, &inp.coupling(), &kd_closures),
        Err(ColumnError::InvalidInput { field: "phi", cell: 3, .. })
    ));
    // bad dt
    let ok = Inputs::clear(n);
    assert!(col.step(0.0, &ok.coupling(), &closures).is_err());
    assert!(col.step(f64::NAN, &ok.coupling(), &closures).is_err());
    // into saltus_core::Error
    let core: saltus_core::Error = err.into();
    assert!(core.to_string().contains("cell 7"));
}

#[test]
fn overflow_of_u_f_is_an_error_naming_time_cell_and_field() {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let n = 10;
    // u ~ G h^2 / (2 mu) overflows
    let params = ColumnParams { pressure_gradient: 1e308, ..ColumnParams::default() };
    let mut col = FluidColumn::new(Grid::uniform(n, 10.0).unwrap(), params).unwrap();
    col.set_time(2.5);
    let inp = Inputs::clear(n);
    let err = col.step(1e10, &inp.coupling(), &closures).unwrap_err();
    println!("{err}");
    match err {
        ColumnError::NonFinite { field, time, .. } => {
            assert_eq!(field, "u_f");
            assert_eq!(time, 2.5 + 1e10);
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(err.to_string().contains("u_f") && err.to_string().contains("t = 10000000002.5"));
}

#[test]
fn steady_not_converged_is_reported() {
    let prandtl = turbulence("type = \"mixing_length\"\nform = \"prandtl\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: prandtl.as_ref(), wall_friction: None };
    let params = ColumnParams { pressure_gradient: 10.0, ..ColumnParams::default() };
    let mut col = FluidColumn::new(Grid::uniform(50, 0.1).unwrap(), params).unwrap();
    let inp = Inputs::clear(50);
    let err = col.solve_steady(&inp.coupling(), &closures, 1e-12, 3).unwrap_err();
    assert!(matches!(err, ColumnError::NotConverged { iterations: 3, .. }), "{err:?}");
    assert!(col.velocity().iter().all(|u| u.is_finite()));
}

#[test]
fn parameters_are_validated() {
    let g = || Grid::uniform(10, 1.0).unwrap();
    for p in [
        ColumnParams { density: 0.0, ..ColumnParams::default() },
        ColumnParams { viscosity: -1.0, ..ColumnParams::default() },
        ColumnParams { relaxation: 0.0, ..ColumnParams::default() },
        ColumnParams { relaxation: 1.5, ..ColumnParams::default() },
        ColumnParams { gravity_x: f64::NAN, ..ColumnParams::default() },
        ColumnParams { top: TopBoundary::Lid { velocity: f64::INFINITY }, ..ColumnParams::default() },
    ] {
        assert!(matches!(FluidColumn::new(g(), p), Err(ColumnError::InvalidParameter { .. })));
    }
}

/// FluidColumn with the two-phase low-Re k-omega (Cheng et al. eqs 21-31) reproduces the
/// Eulerian solver's channel at Re_tau = 587.19 (cases/verification/channel_re590.toml:
/// the same stretched grid, smooth wall, symmetry plane): both are run here, the column to
/// steady state by `solve_steady` and by time steps, the Eulerian one by its own stepping.
/// The two discretisations differ only in the top cell (quadratic against zero-gradient
/// face value), so U, k and omega agree to 0.1 % of their maxima; the total stress is
/// linear, (nu + nu_t) dU/dz = u*^2 (1 - z/h), to 1e-6 u*^2 at every face.
#[test]
fn k_omega_channel_matches_the_eulerian_solver() {
    use saltus_core::scene::Scene;
    use saltus_solvers::eulerian::{Config, Eulerian};
    use saltus_solvers::run::{drive, Ending, Quiet};
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    saltus_closures::link();
    let scene = Scene::from_file_with(root.join("cases/verification/channel_re590.toml"), &[]).expect("scene");
    let cfg = Config::from_scene(&scene).expect("config");
    let (n, ratio, h) = (cfg.cells, scene.domain.stretching, scene.domain.water_depth);
    let mut eul = Eulerian::new(&scene, cfg).expect("solver");
    assert_eq!(drive(&mut eul, &mut Quiet).ending, Ending::Steady);
    let (k_e, w_e) = eul.k_omega().expect("k-omega state");

    let ko = turbulence("type = \"k_omega\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: ko.as_ref(), wall_friction: None };
    let gx = scene.physics.pressure_gradient;
    let params = ColumnParams { pressure_gradient: gx, top: TopBoundary::Symmetry, ..ColumnParams::default() };
    let inp = Inputs::clear(n);
    let u_star = (gx / 1000.0 * h).sqrt();
    let close = |a: &[f64], b: &[f64], what: &str| {
        let max = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / max;
        println!("{what}: largest difference {:.4} % of the maximum", 100.0 * worst);
        assert!(worst < 1e-3, "{what}: largest difference {:.3} % of the maximum", 100.0 * worst);
    };
    // steady solve
    let mut steady = FluidColumn::new(Grid::geometric(n, h, ratio).unwrap(), params).unwrap();
    let rep = steady.solve_steady(&inp.coupling(), &closures, 1e-10, 5000).expect("steady k-omega channel");
    // time stepping (what the DEM solver does), 2000 steps of 0.05 s = 150 h/u*
    let mut stepped = FluidColumn::new(Grid::geometric(n, h, ratio).unwrap(), params).unwrap();
    for _ in 0..2000 {
        stepped.step(0.05, &inp.coupling(), &closures).expect("step");
    }
    for col in [&steady, &stepped] {
        close(col.velocity(), eul.u_f(), "u_f");
        let (k, w) = col.k_omega().expect("k-omega state");
        close(k, k_e, "k");
        close(w, w_e, "omega");
    }
    let zf = steady.grid().faces();
    for (j, (&tau, &z)) in steady.shear_stress().iter().zip(zf).enumerate().take(n).skip(1) {
        let tau = tau / 1000.0 / (u_star * u_star);
        assert!((tau - (1.0 - z / h)).abs() < 1e-6, "face {j}: {tau}");
    }
    println!("k-omega channel: FluidColumn steady in {} iterations (residual {:.1e})", rep.iterations, rep.residual);
}

/// A closure that transports fields but has no two-equation face is still refused, and
/// a lid is refused with k-omega (no wall treatment at a moving lid).
#[test]
fn k_omega_with_a_lid_is_refused() {
    let ko = turbulence("type = \"k_omega\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: ko.as_ref(), wall_friction: None };
    let params = ColumnParams { top: TopBoundary::Lid { velocity: 0.1 }, ..ColumnParams::default() };
    let mut col = FluidColumn::new(Grid::uniform(16, 0.01).unwrap(), params).unwrap();
    let inp = Inputs::clear(16);
    let err = col.step(0.1, &inp.coupling(), &closures).unwrap_err();
    assert!(matches!(err, ColumnError::InvalidParameter { name: "top", .. }), "{err}");
}
