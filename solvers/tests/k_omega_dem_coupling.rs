//! The two-phase k-omega closure as the DEM coupling evaluates it, term by term against
//! Cheng, Chauchat, Hsu & Calantoni eqs 7-13 and 21-35 written out here from the grains of
//! a frozen state (docs/notes/k_omega_dem_coupling.md). Run with
//! `cargo test -p saltus-solvers --release --test k_omega_dem_coupling -- --nocapture` for
//! the table of the terms.

mod common;

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::Stepper;

const NU: f64 = 1e-6;
const RHO_F: f64 = 1000.0;
const G: f64 = 9.81;
const SPHERICITY: f64 = 0.594;

/// Table 1 of Cheng et al. with C_s = 1 and the text's C_t = 1/6, sigma_c = 1.
struct Table1;
impl Table1 {
    const ALPHA_0: f64 = 1.0 / 9.0;
    const ALPHA_STAR_0: f64 = 0.024;
    const RE_K: f64 = 6.0;
    const RE_W: f64 = 2.95;
    const RE_BETA: f64 = 8.0;
    const C_MU: f64 = 0.09;
    const C_S: f64 = 1.0;
    const C_T: f64 = 1.0 / 6.0;
    const C_1W: f64 = 0.52;
    const C_2W: f64 = 0.072;
    const C_3W: f64 = 0.14;
    const C_4W: f64 = 0.0;
    const SIGMA_C: f64 = 1.0;
    const PHI_B: f64 = 0.55;
}

/// The tiny coupled bed of case 1 with Cheng's k-omega (table 1, C_s = 1), his drag law
/// (Haider-Levenspiel with Di Felice's hindrance, eqs 7-13) and the eddy interaction
/// model, the relative velocity of the drag damping averaged from `start` (eq 24).
fn scene(start: f64) -> Scene {
    saltus_closures::link();
    let mut set: Vec<String> = common::TINY_COUPLED_BED.iter().map(|s| s.to_string()).collect();
    set.extend([
        format!("closures.turbulence={{type=\"k_omega\", wall=\"rough\", c_s=1.0, slip_average_start={start}}}"),
        format!("closures.drag={{type=\"haider_levenspiel\", sphericity={SPHERICITY}}}"),
        "closures.hindrance={type=\"di_felice\"}".to_string(),
        "closures.fluctuation={type=\"eim\", c0=3.0}".to_string(),
        "solver.lagrangian.end_time=1.0".to_string(),
        "solver.lagrangian.stats_start=0.0".to_string(),
    ]);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    Scene::from_file_with(path, &set).expect("scene")
}

/// Volume of the slice a < z < b of a sphere of centre height zc and radius r.
fn slice_volume(zc: f64, r: f64, a: f64, b: f64) -> f64 {
    let (lo, hi) = ((a - zc).max(-r), (b - zc).min(r));
    if hi <= lo {
        return 0.0;
    }
    let prim = |s: f64| r * r * s - s * s * s / 3.0;
    std::f64::consts::PI * (prim(hi) - prim(lo))
}

/// C_D of eqs 7-11 without the hindrance at Reynolds number `re`.
fn haider_levenspiel(re: f64) -> f64 {
    let e = SPHERICITY;
    let a = (2.3288 - 6.4581 * e + 2.4486 * e * e).exp();
    let b = 0.0964 + 0.5565 * e;
    let c = (4.905 - 13.8944 * e + 18.4222 * e * e - 10.2599 * e * e * e).exp();
    let d = (1.4681 + 12.2584 * e - 20.7322 * e * e + 15.8855 * e * e * e).exp();
    24.0 / re * (1.0 + a * re.powf(b)) + c / (1.0 + d / re)
}

/// beta of eq 23 with C_D of eq 7 (hindrance eqs 12-13) at relative speed `ur` and phi.
fn beta_eq23(ur: f64, phi: f64, d: f64) -> f64 {
    let re = (1.0 - phi) * ur * d / NU;
    let n = 3.7 - 0.65 * (-(1.5 - re.log10()).powi(2) / 2.0).exp();
    let cd = (1.0 - phi).powf(2.0 - n) * haider_levenspiel(re);
    0.75 * RHO_F * cd * ur / d
}

/// The frozen state: the DEM after 0.2 s of flow, stopped just after a fluid update, with
/// the column's velocity, k and omega before that update.
struct Frozen<'a> {
    m: Lagrangian<'a>,
    u_before: Vec<f64>,
    k_before: Vec<f64>,
    w_before: Vec<f64>,
}

fn frozen(s: &Scene) -> Frozen<'_> {
    let cfg = Config::from_scene(s).expect("config");
    let mut m = Lagrangian::new(s, cfg).expect("solver");
    m.deposit().expect("deposition");
    let (mut u_before, mut k_before, mut w_before) = (Vec::new(), Vec::new(), Vec::new());
    loop {
        if let Some(col) = m.column() {
            u_before = col.velocity().to_vec();
            if let Some((k, w)) = col.k_omega() {
                k_before = k.to_vec();
                w_before = w.to_vec();
            }
        }
        if let Some(end) = m.step_unit() {
            panic!("ended before 0.2 s: {end:?}");
        }
        // a unit that ends on a check of the state rather than a fluid update goes on
        let updated = (m.steps() - 1).is_multiple_of(m.fluid_every());
        if m.time() >= 0.2 && updated && !k_before.is_empty() {
            return Frozen { m, u_before, k_before, w_before };
        }
    }
}

/// Cell averages of the grains by exact slice volumes: phi and the volume-averaged
/// velocity per cell.
fn cell_averages(m: &Lagrangian<'_>) -> (Vec<f64>, Vec<[f64; 3]>) {
    let (n, dz, base, vc) = (m.cells(), m.dz(), m.column_base(), m.cell_volume());
    let p = m.particles();
    let mut vol = vec![0.0; n];
    let mut mom = vec![[0.0; 3]; n];
    for a in 0..p.len() {
        let (zc, r) = (p.z[a] - base, p.radius[a]);
        for c in 0..n {
            let w = slice_volume(zc, r, c as f64 * dz, (c + 1) as f64 * dz);
            vol[c] += w;
            mom[c][0] += w * p.vx[a];
            mom[c][1] += w * p.vy[a];
            mom[c][2] += w * p.vz[a];
        }
    }
    let phi: Vec<f64> = vol.iter().map(|v| v / vc).collect();
    let vs = vol.iter().zip(&mom).map(|(&v, m)| if v > 0.0 { m.map(|x| x / v) } else { [0.0; 3] }).collect();
    (phi, vs)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (a.abs().max(b.abs()) + 1e-300)
}

#[test]
fn every_term_of_eqs_21_to_29_is_the_papers_on_the_grains_of_a_frozen_dem_state() {
    // eq 24 with t_0 past the end: U_r is the current relative velocity of the cell
    // averages, beta eq 23 from it
    let s = scene(1e9);
    let f = frozen(&s);
    let m = &f.m;
    let col = m.column().expect("coupled");
    let d = m.material().d;
    let rho_p = m.material().rho_p;
    let n = m.cells();
    let zc = col.grid().centres();

    // the inputs: phi of the slices (eq 14 at one DEM step, no smoothing of eq 17), the
    // grains' volume average, the fluid velocity the grains saw
    let (phi, vs) = cell_averages(m);
    for (c, (&a, &b)) in phi.iter().zip(m.volume_fraction()).enumerate() {
        assert!(close(a, b, 1e-9), "phi of cell {c}: slices {a}, coupling {b}");
    }
    let beta = col.damping_drag().expect("k-omega state");
    let exchange = col.exchange_drag();
    let mut paper_beta = vec![0.0; n];
    for c in 0..n {
        if phi[c] <= 0.0 {
            continue;
        }
        let ur = [f.u_before[c] - vs[c][0], -vs[c][1], -vs[c][2] / (1.0 - phi[c])];
        let ur = (ur[0] * ur[0] + ur[1] * ur[1] + ur[2] * ur[2]).sqrt();
        paper_beta[c] = beta_eq23(ur, phi[c], d);
        assert!(close(beta[c], paper_beta[c], 1e-9), "beta of cell {c}: {} against eq 23 {}", beta[c], paper_beta[c]);
    }

    // every term, written out from table 1 with the inputs above
    let terms = col.two_equation_terms().expect("terms");
    let shear = col.shear_rate();
    let omega_bed = {
        // eqs 34-35 with u* of the forcing, k_s = 2.5 d, K_r = 65 (the closure's, docs/closures/k_omega.md)
        let u = col.params().friction_velocity.expect("u* of the forcing");
        let ks = 2.5 * d * u / NU;
        let sr = if ks < 5.0 {
            (200.0 / ks).powi(2)
        } else {
            65.0 / ks + ((200.0 / ks).powi(2) - 65.0 / ks) * (5.0 - ks).exp()
        };
        sr * u * u / NU
    };
    let s_m1 = rho_p / RHO_F - 1.0;
    // g cos(alpha), the slope being sin(alpha)
    let gn = s.physics.gravity * (1.0 - s.physics.slope * s.physics.slope).sqrt();
    assert_eq!(s.physics.gravity, G);
    let mut shown = 0;
    eprintln!("cell z(mm) phi | beta: exchange/phi eq23 | St lambda | eq 21: P, C_mu* k w, drag, buoy | eq 26: P_w, C_2w w^2, C_3w drag, Gamma w_bed/T");
    // from the top down, so that the cells shown are the top of the deposit
    for c in (0..n).rev() {
        let (k, w) = (f.k_before[c].max(0.0), f.w_before[c]);
        let ph = m.volume_fraction()[c];
        let eps = 1.0 - ph;
        let re_t = k / (NU * w);
        let a_star = (Table1::ALPHA_STAR_0 + re_t / Table1::RE_K) / (1.0 + re_t / Table1::RE_K); // eq 28
        let nu_t = a_star * k / w; // eq 29
        let r4 = (re_t / Table1::RE_BETA).powi(4);
        let c_mu_star = Table1::C_MU * (4.0 / 15.0 + r4) / (1.0 + r4); // eq 22
        let c_1w_star = Table1::C_1W / a_star * (Table1::ALPHA_0 + re_t / Table1::RE_W) / (1.0 + re_t / Table1::RE_W); // eq 27
        let b = paper_beta[c];
        // eq 25: St = t_p / t_l, t_p = rho_s / beta, t_l = C_t / (C_mu omega)
        let st = if b > 0.0 { rho_p / b / (Table1::C_T / (Table1::C_MU * w)) } else { f64::INFINITY };
        let lambda = (-Table1::C_S * st).exp();
        let (l, r) = (c.saturating_sub(1), (c + 1).min(n - 1));
        let dphidz = (m.volume_fraction()[r] - m.volume_fraction()[l]) / (zc[r] - zc[l]);
        let production = eps * nu_t * shear[c] * shear[c]; // tau_ft/rho_f : grad u, eq 20
        let dissipation = c_mu_star * k * w;
        let drag = 2.0 * b * (1.0 - lambda) * ph * k / (RHO_F * eps);
        // -(1/eps) (nu_t/sigma_c) (s - 1) g . grad phi, g pointing down
        let buoyancy = nu_t / (eps * Table1::SIGMA_C) * s_m1 * gn * dphidz;
        let gamma = 0.5 * ((500.0 * (ph - Table1::PHI_B)).tanh() + 1.0); // eq 32
        let drag_w = Table1::C_3W * 2.0 * b * (1.0 - lambda) * ph * w / (RHO_F * eps);
        let buoy_w = Table1::C_4W * w / k.max(1e-300) * buoyancy;
        let inv_t = (Table1::C_2W * w + drag_w / w - buoy_w / w).max(0.0); // eq 33
                                                                           // C_1w* (omega/k) tau_ft/rho_f : grad u, with (omega/k) nu_t = alpha* (finite as k -> 0)
        let production_w = c_1w_star * a_star * eps * shear[c] * shear[c];
        let relax = if gamma > 0.0 { gamma * omega_bed * inv_t } else { 0.0 };
        // the closure's split into sources and implicit sink rates
        let ks = production + buoyancy.max(0.0);
        let kk = dissipation + drag + (-buoyancy).max(0.0);
        assert!(close(terms.k_source[c], ks, 1e-9), "k source of cell {c}: {} against {ks}", terms.k_source[c]);
        assert!(close(terms.k_sink[c] * k, kk, 1e-9), "k sink of cell {c}: {} against {kk}", terms.k_sink[c] * k);
        let ws = production_w + relax + buoy_w.max(0.0);
        assert!(
            close(terms.omega_source[c], ws, 1e-9),
            "omega source of cell {c}: {} against {ws}",
            terms.omega_source[c]
        );
        let wk = Table1::C_2W * w * w + drag_w + (-buoy_w).max(0.0);
        assert!(
            close(terms.omega_sink[c] * w, wk, 1e-9),
            "omega sink of cell {c}: {} against {wk}",
            terms.omega_sink[c] * w
        );
        if ph > 0.02 && ph < 0.5 && shown < 8 {
            shown += 1;
            eprintln!(
                "{c:4} {:6.2} {ph:5.3} | {:9.1} {b:9.1} | {st:6.2} {lambda:6.3} | {production:9.2e} {dissipation:9.2e} {drag:9.2e} {buoyancy:10.2e} | {production_w:9.2e} {:9.2e} {drag_w:9.2e} {relax:9.2e}",
                zc[c] * 1e3,
                exchange[c] / ph,
                Table1::C_2W * w * w
            );
        }
    }
    assert!(shown > 0, "no cell of the sheet (0.02 < phi < 0.5) in the frozen state");
}
