//! Turbulent suspension in the Eulerian solver through the mean-field face of the
//! fluctuation closures: the Rouse profile (docs/verification.md, benchmark 3), the Ito form of
//! the drift against its own analytic profile, and Cheng et al.'s dilute channels (section
//! 3.1, table 2). Run with `cargo test -p saltus-solvers --release --test suspension`.

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{drive, Ending, Quiet, Stepper};

fn case(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(rel)
}

fn load(rel: &str, set: &[&str]) -> Scene {
    saltus_closures::link();
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Scene::from_file_with(case(rel), &set).expect("scene")
}

fn run(s: &Scene) -> (Eulerian<'_>, Ending) {
    let cfg = Config::from_scene(s).expect("config");
    let mut m = Eulerian::new(s, cfg).expect("solver");
    let ending = drive(&mut m, &mut Quiet).ending;
    (m, ending)
}

/// Constants of `cases/verification/rouse_parabolic.toml`: depth, u*, Sc, and the Stokes
/// terminal velocity (s - 1) g d^2 / (18 nu) of its grains.
const H: f64 = 0.1;
const U_STAR: f64 = 0.05;
const SC: f64 = 0.7;
const KAPPA: f64 = 0.41;

fn stokes_velocity() -> f64 {
    1.65 * 9.81 * 1e-8 / (18.0 * 1e-6)
}

/// Largest relative deviation of phi / phi(cell a) from `shape(z) / shape(z_a)` over
/// z_a <= z <= top.
fn worst_deviation(m: &Eulerian<'_>, a: usize, top: f64, shape: impl Fn(f64) -> f64) -> f64 {
    let (z, phi) = (m.z(), m.phi());
    (a..m.len())
        .filter(|&i| z[i] <= top)
        .map(|i| (phi[i] / phi[a] / (shape(z[i]) / shape(z[a])) - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Benchmark 3: under nu_t = kappa u* z (1 - z/h) and D = nu_t / Sc (gradient form,
/// Chassagne eq 4.4) the steady suspension is the Rouse profile
/// phi/phi_a = [((h - z)/z) (a/(h - a))]^P, P = w_s Sc / (kappa u*), within 0.5 % for
/// a <= z <= 0.9 h at 200 cells; the sediment volume is conserved to round-off and the
/// fitted Rouse number of the summary (Cheng eq 38 over 0.1 h - 0.5 h) is P within 0.5 %.
#[test]
fn rouse_profile_under_a_parabolic_eddy_viscosity() {
    let s = load("cases/verification/rouse_parabolic.toml", &[]);
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let p = stokes_velocity() * SC / (KAPPA * U_STAR);
    // a: the centre of cell 10, 0.0525 h
    let worst = worst_deviation(&m, 10, 0.9 * H, |z| ((H - z) / z).powf(p));
    assert!(worst < 5e-3, "Rouse profile off by {worst:e}");
    assert!(m.mass_error() < 1e-12, "mass error {:e}", m.mass_error());
    let ro = m.report(&ending, &Default::default()).summary.rouse_number.expect("rouse number");
    assert!((ro / p - 1.0).abs() < 5e-3, "fitted Rouse number {ro} against P = {p}");
}

/// The Ito form of the drift (flux -d(D phi)/dz, the diffusion limit of a random walk whose
/// draws are set where they are drawn) under the same parabolic D: w_s phi = -d(D phi)/dz
/// gives D phi proportional to the Rouse profile, phi ~ [(h - z)/z]^P / (z (h - z)); within
/// 0.5 % for a <= z <= 0.8 h (the profile is singular at the surface, where D vanishes, as
/// (h - z)^(P - 1)).
#[test]
fn ito_drift_matches_its_analytic_profile() {
    let s = load("cases/verification/rouse_parabolic.toml", &["closures.fluctuation.mean_field=\"ito\""]);
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let p = stokes_velocity() * SC / (KAPPA * U_STAR);
    let worst = worst_deviation(&m, 10, 0.8 * H, |z| ((H - z) / z).powf(p) / (z * (H - z)));
    assert!(worst < 5e-3, "Ito profile off by {worst:e}");
    assert!(m.mass_error() < 1e-12, "mass error {:e}", m.mass_error());
}

fn rouse_number(rel: &str, set: &[&str]) -> f64 {
    let s = load(rel, set);
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady, "{rel} {set:?}");
    assert!(m.mass_error() < 1e-12, "{rel}: mass error {:e}", m.mass_error());
    m.report(&ending, &Default::default()).summary.rouse_number.expect("rouse number")
}

/// Cheng et al. section 3.1, NS1 of Muste et al. 2005 (table 2): k-omega channel with the
/// eddy interaction model (C0 = 3, Ito mean-field form); Cheng's Rouse number 0.86 (fig 3b)
/// within 10 %, steady, the sediment volume conserved to round-off.
#[test]
fn muste_ns1_rouse_number_within_ten_percent_of_cheng() {
    let ro = rouse_number("cases/cheng/dilute_muste_ns1.toml", &[]);
    assert!((ro / 0.86 - 1.0).abs() < 0.1, "Rouse number {ro} against 0.86");
}

/// Cheng et al. figure 2c (Kiger & Pan 2002): the suspension rises with C0, i.e. the Rouse
/// number falls strictly over C0 = 1, 2, 3, 4; and the gradient form (well mixed) suspends
/// more than the Ito form, whose drift grad(D) carries grains towards the wall.
#[test]
fn kiger_pan_rouse_number_falls_with_c0() {
    let rel = "cases/cheng/dilute_kiger_pan.toml";
    let ro: Vec<f64> = (1..=4).map(|c| rouse_number(rel, &[&format!("closures.fluctuation.c0={c}")])).collect();
    assert!(ro.windows(2).all(|w| w[1] < w[0]), "Rouse numbers over C0 = 1-4: {ro:?}");
    let gradient = rouse_number(rel, &["closures.fluctuation.mean_field=\"gradient\""]);
    assert!(gradient < ro[2], "gradient {gradient} against Ito {}", ro[2]);
}

/// The 3 mm PMMA grains of the Revil-Baudard scenes (rho_p = 1192), uniformly suspended at
/// phi = 1e-3 in still water, under the Dallavalle drag C_D = 0.4 + 24.4/Re (Chassagne
/// eq 2.11) without hindrance: away from the settling fronts the wall-normal flux is
/// phi w_p with w_p = eps w_r and w_r the terminal slip of the quasi-static balance
/// (eqs 2.5-2.6) under the mixture's buoyancy, C(w_r) w_r = eps (rho_p - rho_f) g with
/// C = (3/4) rho_f nu (0.4 Re + 24.4) / d^2, i.e. the root of
/// 0.3 rho_f w^2 / d + 18.3 rho_f nu w / d^2 = eps (rho_p - rho_f) g (Re ~ 300). The drag
/// depends on the settling slip it sets: with that slip lagged (Picard) the step iterates
/// w <- F / C(w), whose slope -d ln C / d ln Re = -0.83 here converges by 17 % a step
/// from the Stokes velocity (0.94 m/s) of the first step; the Newton step of the phi
/// equation converges quadratically: within 1e-9 after 12 steps, and steady (two
/// successive steps agree).
#[test]
fn dilute_settling_reaches_the_terminal_velocity_of_the_drag_law() {
    let s = load(
        "cases/revil_baudard2015/mobile_bed_kinetic_mixing_length.toml",
        &[
            "physics.pressure_gradient=0.0",
            "domain.bed_height=0.0",
            "domain.suspension_phi=1e-3",
            "domain.water_depth=0.1",
            "domain.cells=50",
            "closures.drag={type=\"dallavalle\"}",
            "closures.hindrance={type=\"none\"}",
            "closures.fluctuation={type=\"none\"}",
            "solver.eulerian.dt_initial=1e-3",
            "solver.eulerian.dt_max=1e-3",
        ],
    );
    let mut m = Eulerian::new(&s, Config::from_scene(&s).expect("config")).expect("solver");
    let (rho_f, rho_p, nu, d, g, phi) = (1000.0, 1192.0, 1e-6, 3e-3, 9.81, 1e-3);
    let eps: f64 = 1.0 - phi;
    let (a, b, c) = (0.3 * rho_f / d, 18.3 * rho_f * nu / (d * d), -eps * (rho_p - rho_f) * g);
    let w_r = (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    let expected = -eps * w_r;
    // the middle face: the upper front has fallen 1.2 cm in 12 ms of 1 ms steps
    let j = m.len() / 2;
    let mut last = 0.0;
    for _ in 0..12 {
        assert!(m.step_unit().is_none());
        last = m.flux()[j] / m.phi()[j];
    }
    assert!(m.step_unit().is_none());
    let w = m.flux()[j] / m.phi()[j];
    assert!((w / expected - 1.0).abs() < 1e-9, "settling velocity {w} m/s against {expected} m/s");
    assert!((w / last - 1.0).abs() < 1e-9, "successive settling velocities {last} and {w} m/s");
}

/// The four Revil-Baudard mobile-bed scenes with turbulent suspension
/// (`schmidt` drift, Chassagne eqs 4.3-4.4; kinetic theory or mu(I), mixing length or
/// k-omega) reach the steady criterion of the scene (relative rates below 1e-6 /s for 20
/// steps) before end_time, with the sediment volume conserved to round-off and grains in
/// suspension 2 cm above the bed surface (the data: phi 0.01-0.02 there). They held a
/// period-2 cycle of the settling slip before the Newton step of the wall-normal drag
/// (residual 1.5-2.5 /s to end_time).
#[test]
fn revil_baudard_suspension_sheet_flows_reach_steady_state() {
    for scene in ["kinetic_mixing_length", "mu_i_mixing_length", "kinetic_k_omega", "mu_i_k_omega"] {
        let s = load(&format!("cases/revil_baudard2015/mobile_bed_{scene}.toml"), &[]);
        let (m, ending) = run(&s);
        assert_eq!(ending, Ending::Steady, "{scene}: residual {:e} /s at t = {} s", m.residual(), m.time());
        assert!(m.mass_error() < 1e-13, "{scene}: mass error {:e}", m.mass_error());
        let z_b = saltus_solvers::measures::bed_aligned::half_bed_level(m.z(), m.phi()).expect("a bed surface");
        let suspended = saltus_solvers::measures::bed_aligned::interpolate(m.z(), m.phi(), z_b + 0.02);
        assert!(suspended > 1e-4, "{scene}: phi 2 cm above the bed {suspended:e}");
    }
}

/// Terminal velocity (m/s) of one grain of the scene under its drag law in still fluid:
/// the root of C_D(w d / nu) w^2 = (4/3) (rho_p / rho_f - 1) g d (drag = submerged weight).
fn terminal_velocity(s: &Scene) -> f64 {
    let drag = s.closures.drag.as_ref().expect("a drag law");
    let (d, nu) = (s.particles.diameter, s.fluid.viscosity);
    let target = 4.0 / 3.0 * (s.particles.density / s.fluid.density - 1.0) * s.physics.gravity * d;
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let w = 0.5 * (lo + hi);
        if drag.cd(w * d / nu) * w * w < target {
            lo = w;
        } else {
            hi = w;
        }
    }
    0.5 * (lo + hi)
}

/// Expected number of the scene's DEM grains whose centres lie in the Rouse fit range
/// (0.1 h to 0.5 h above z_b, solvers/src/measures/rouse.rs) in the diffusion limit of the particle
/// face: the `eim` draws diffuse in the Ito form (docs/closures/fluctuation.md), the wall
/// holds a grain's centre at the contact height d/2 (no flux below it), so the steady
/// profile above d/2 is D phi ~ exp(-int_{d/2}^z w_s / D dz') (w_s phi = -d(D phi)/dz).
/// D = the closure's diffusivity from k and omega of the cell holding z, read as the DEM
/// reads them ([`FluidField::cell`]), on the steady k-omega column of the Eulerian solver
/// (the fluid both faces see: the suspension is dilute); midpoint quadrature over 200
/// sub-steps a cell.
fn grains_in_the_rouse_range(rel: &str) -> f64 {
    use saltus_core::{FlowScales, TurbulencePoint};
    use saltus_solvers::lagrangian::coupling::drag::FluidField;
    let s = load(rel, &[]);
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady, "{rel}");
    let (k, omega) = m.k_omega().expect("a k-omega column");
    let (n, dz) = (m.len(), m.dz()[0]);
    let field = FluidField::at_rest(n, dz, 0.0);
    let fl = s.closures.fluctuation.as_ref().expect("a fluctuation closure");
    let diffusivity = |z: f64| {
        let c = field.cell(z);
        fl.diffusivity(
            &TurbulencePoint { k: k[c], omega: omega[c], ..TurbulencePoint::default() },
            &FlowScales::default(),
        )
    };
    let w_s = terminal_velocity(&s);
    let (z_b, h) = (s.domain.bed_height, s.domain.water_depth);
    let (bottom, top) = (0.5 * s.particles.diameter, n as f64 * dz);
    let steps = 200 * n;
    let step = (top - bottom) / steps as f64;
    // ln of the unnormalised profile, kept in logs: the exponent reaches hundreds
    let mut exponent = 0.0;
    let log_phi: Vec<(f64, f64)> = (0..steps)
        .map(|i| {
            let z = bottom + (i as f64 + 0.5) * step;
            let d = diffusivity(z);
            assert!(d > 0.0, "{rel}: no diffusivity at z = {z}");
            exponent += w_s / d * step;
            (z, -exponent - d.ln())
        })
        .collect();
    let peak = log_phi.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
    let total: f64 = log_phi.iter().map(|p| (p.1 - peak).exp()).sum();
    let range = (z_b + 0.1 * h)..=(z_b + 0.5 * h);
    let inside: f64 = log_phi.iter().filter(|p| range.contains(&p.0)).map(|p| (p.1 - peak).exp()).sum();
    s.solver.lagrangian.particles.expect("a particle count") as f64 * inside / total
}

/// The DEM face of `eim` on Cheng's two dilute channels. Kiger & Pan's
/// grains (w_s = 2.24 cm/s) rest at d/2 = 97.5 um, z+ = 2.8, where the wall cell gives
/// D = 0.012 nu: the steady state holds less than one of the 476 grains in the Rouse fit
/// range (so the DEM has no Rouse number to give; the runs: no grain rises 6 um off its
/// contact). NS1's (d/2 = 115 um, z+ = 4.8, the second cell, D = 1.6 nu) put more than 10
/// of the 803 there, enough for the DEM to fit a Rouse number (docs/notes/kiger_pan_rouse_number.md).
#[test]
fn the_dem_face_suspends_nothing_in_kiger_pan_and_enough_in_ns1() {
    let kiger_pan = grains_in_the_rouse_range("cases/cheng/dilute_kiger_pan.toml");
    assert!(kiger_pan < 1.0, "Kiger & Pan: {kiger_pan} grains in the Rouse range");
    let ns1 = grains_in_the_rouse_range("cases/cheng/dilute_muste_ns1.toml");
    assert!(ns1 > 10.0, "NS1: {ns1} grains in the Rouse range");
}
