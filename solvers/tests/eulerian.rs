//! Verification of the Eulerian two-fluid solver against analytical solutions
//! (docs/verification.md, benchmarks 1, 5, 6), conservation, and the Chassagne et al. 2023
//! reference case. Run with `cargo test -p saltus-solvers --release --test eulerian`.

use std::path::Path;

use saltus_core::scene::{parse_table, Scene};
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{drive, Ending, Quiet};

fn scene(text: &str) -> Scene {
    saltus_closures::link();
    let t = parse_table(text, Path::new("test.toml")).expect("toml");
    Scene::from_table(t, Path::new("test.toml")).expect("scene")
}

fn run(s: &Scene) -> (Eulerian<'_>, Ending) {
    let cfg = Config::from_scene(s).expect("config");
    let mut m = Eulerian::new(s, cfg).expect("solver");
    let ending = drive(&mut m, &mut Quiet).ending;
    (m, ending)
}

const CLEAR: &str = r#"
[fluid]
density = 1000.0
viscosity = 1.0e-6
[particles]
diameter = 1.0e-3
density = 2650.0
[closures.granular]
type = "mu_i"
"#;

/// The Eulerian solver run to a steady state at round-off: the laminar benchmarks are
/// exact at the cell centres.
const TO_MACHINE_PRECISION: &str = "
[solver]
type = \"eulerian\"
[solver.eulerian]
steady_tolerance = 1e-13
dt_max = 1e4
end_time = 1e6
";

/// Benchmark 1: laminar Couette flow, u = U z / H at the cell centres.
#[test]
fn laminar_couette_is_exact() {
    let s = scene(&format!(
        "{CLEAR}
[domain]
water_depth = 0.01
cells = 40
top = \"lid\"
lid_velocity = 0.02
{TO_MACHINE_PRECISION}"
    ));
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let worst = m.z().iter().zip(m.u_f()).map(|(z, u)| (u - 0.02 * z / 0.01).abs() / 0.02).fold(0.0, f64::max);
    assert!(worst < 1e-10, "max relative error {worst:e}");
}

/// Benchmark 1: laminar open channel driven by G, u = G/(2 mu) (2 H z - z^2), exact at the
/// cell centres (quadratic profile, second-order wall gradient, zero-stress top face).
#[test]
fn laminar_open_channel_is_exact() {
    let g = 0.5;
    let h = 0.01;
    let s = scene(&format!(
        "{CLEAR}
[physics]
pressure_gradient = {g}
[domain]
water_depth = {h}
cells = 25
{TO_MACHINE_PRECISION}"
    ));
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let mu = 1e-3;
    let umax = g / (2.0 * mu) * h * h;
    let worst = m
        .z()
        .iter()
        .zip(m.u_f())
        .map(|(z, u)| (u - g / (2.0 * mu) * (2.0 * h * z - z * z)).abs() / umax)
        .fold(0.0, f64::max);
    assert!(worst < 1e-10, "max relative error {worst:e}");
}

/// Benchmark 5: hindered settling. In the uniform suspension the particles fall at
/// (1 - phi) u_r with 0.4 u_r^2 + 24.4 nu u_r / d = (4/3)(s - 1) g d (1 - phi)^(1 + zeta)
/// (Dallavalle drag, Richardson-Zaki zeta = 3.1), and the suspension/clear-water interface
/// falls at that speed (Kynch). Mass is conserved to round-off.
#[test]
fn hindered_settling_velocity_and_interface() {
    let (phi0, d, s_ratio, nu): (f64, f64, f64, f64) = (0.1, 0.5e-3, 2.65, 1e-6);
    let h = 0.2;
    let s = scene(&format!(
        "
[fluid]
density = 1000.0
viscosity = {nu}
[particles]
diameter = {d}
density = {rho_p}
[closures.granular]
type = \"mu_i\"
[closures.hindrance]
type = \"richardson_zaki\"
exponent = 3.1
[domain]
water_depth = {h}
suspension_phi = {phi0}
cells = 400
[solver]
type = \"eulerian\"
[solver.eulerian]
end_time = 1.0
dt_max = 2e-3
",
        rho_p = 1000.0 * s_ratio
    ));
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::EndTime);
    let g = 9.81;
    let rhs = 4.0 / 3.0 * (s_ratio - 1.0) * g * d * (1.0 - phi0).powf(1.0 + 3.1);
    let b = 24.4 * nu / d;
    let ur = (-b + (b * b + 4.0 * 0.4 * rhs).sqrt()) / (2.0 * 0.4);
    let ws = (1.0 - phi0) * ur;
    // mid-column cell, still in the uniform suspension
    let derived = m.derived();
    let i = m.len() / 4;
    assert!((m.phi()[i] - phi0).abs() < 1e-9, "phi in the suspension {}", m.phi()[i]);
    let wp = derived.w_p[i];
    assert!((wp + ws).abs() < 1e-6 * ws, "w_p = {wp}, Kynch/Richardson-Zaki -{ws}");
    // interface: mid level of the phi jump, against H - ws t, within 2 cells
    let z_half = m
        .z()
        .windows(2)
        .zip(m.phi().windows(2))
        .find(|(_, p)| p[0] >= 0.5 * phi0 && p[1] < 0.5 * phi0)
        .map(|(z, p)| z[0] + (p[0] - 0.5 * phi0) / (p[0] - p[1]) * (z[1] - z[0]))
        .expect("interface");
    let expected = h - ws * m.time();
    assert!((z_half - expected).abs() < 2.0 * h / 400.0, "interface {z_half} m, expected {expected} m");
    assert!(m.mass_error() < 1e-12, "mass error {:e}", m.mass_error());
}

/// Constants of `cases/verification/dry_mu_i_incline.toml` and the mu_i defaults
/// (Chassagne et al. 2023 eqs 1.1-1.2).
const TAN_A: f64 = 0.55;
const MU_S: f64 = 0.35;
const MU_2: f64 = 0.97;
const I0: f64 = 0.69;
const PHI_C: f64 = 0.61;
const B_PHI: f64 = 0.31;
const RHO_P: f64 = 2500.0;
const RHO_F: f64 = 1.2;
const G: f64 = 9.81;
const D: f64 = 1e-3;
const H: f64 = 0.02;
/// column height: H + 5 d of air
const L_COL: f64 = 0.025;
const BED_PHI: f64 = 0.5536107869830157;

/// I of mu(I) = mu (mu_s <= mu < mu_2), Chassagne 2023 eq 1.1 inverted.
fn inertial_number_of(mu: f64) -> f64 {
    I0 * (mu - MU_S).max(0.0) / (MU_2 - mu)
}

/// Benchmark 6 (docs/verification.md), the Bagnold profile of a dense mu(I) layer without fluid:
/// mu(I) = tan(alpha), phi = phi(I) uniform,
/// u(z) = (2 I / (3 d)) sqrt(phi g cos) [H^1.5 - (H - z)^1.5].
fn bagnold(z: f64) -> f64 {
    let i = inertial_number_of(TAN_A);
    let phi = PHI_C / (1.0 + B_PHI * i);
    let cos_a = 1.0 / (1.0 + TAN_A * TAN_A).sqrt();
    2.0 * i / (3.0 * D) * (phi * G * cos_a).sqrt() * (H.powf(1.5) - (H - z.min(H)).powf(1.5))
}

/// The same steady uniform layer with the fluid the scene has (air): the two-fluid
/// equations at steady state without wall-normal flux give p = (rho_p - rho_f) g cos m(z)
/// with m(z) the sediment height above z, and (the air's own viscous stress in the layer
/// being ~1e-5 of the total) a grain shear stress that carries the whole weight component
/// above z, grains, entrained air and the air layer on top:
/// tau = g sin [rho_p m + rho_f (L - z - m)]. Then I from mu(I) = tau / p, phi = phi(I),
/// dm/dz = -phi and du/dz = I sqrt(p / rho_p) / d, integrated upwards from the bottom
/// (m(0) = the inventory) by the midpoint rule on 10^5 steps (error ~1e-8 relative).
/// Returns u at the sorted heights `zs`.
fn bagnold_with_fluid(zs: &[f64]) -> Vec<f64> {
    let cos_a = 1.0 / (1.0 + TAN_A * TAN_A).sqrt();
    let sin_a = TAN_A * cos_a;
    let gw = (RHO_P - RHO_F) * G * cos_a;
    // (dm/dz, du/dz) at height z with sediment m above
    let rate = |z: f64, m: f64| {
        let p = gw * m;
        if p <= 0.0 {
            return (0.0, 0.0);
        }
        let tau = G * sin_a * (RHO_P * m + RHO_F * (L_COL - z - m));
        // the stress of the air above exceeds mu_2 p only within ~1e-6 m of the surface
        let i = inertial_number_of((tau / p).min(MU_2 - 1e-9));
        (-PHI_C / (1.0 + B_PHI * i), i * (p / RHO_P).sqrt() / D)
    };
    let steps = 100_000;
    let dz = 1.05 * H / steps as f64;
    let (mut z, mut m, mut u) = (0.0, BED_PHI * H, 0.0);
    let mut out = Vec::with_capacity(zs.len());
    for _ in 0..steps {
        let (dm1, _) = rate(z, m);
        let (dm, du) = rate(z + 0.5 * dz, (m + 0.5 * dz * dm1).max(0.0));
        while out.len() < zs.len() && zs[out.len()] <= z + dz {
            out.push(u + du * (zs[out.len()] - z));
        }
        z += dz;
        m = (m + dm * dz).max(0.0);
        u += du * dz;
    }
    while out.len() < zs.len() {
        out.push(u);
    }
    out
}

/// Benchmark 6: dense mu(I) layer of H = 20 d under air on an incline
/// (`cases/verification/dry_mu_i_incline.toml`) at `cells` cells over the column (5/4 of
/// them across the layer). Returns the largest deviation of u_p over the layer from the
/// Bagnold profile and from the profile with the fluid, both relative to the surface
/// velocity, and whether the run reached steady state.
fn dry_incline_error(cells: usize) -> (f64, f64, bool) {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/verification/dry_mu_i_incline.toml");
    let s = Scene::from_file_with(&file, &[format!("domain.cells={cells}")]).expect("scene");
    let (m, ending) = run(&s);
    assert!(m.mass_error() < 1e-10, "mass error {:e}", m.mass_error());
    let layer: Vec<(f64, f64)> = m.z().iter().zip(m.u_p()).filter(|(&z, _)| z < H).map(|(&z, &u)| (z, u)).collect();
    let zs: Vec<f64> = layer.iter().map(|l| l.0).collect();
    let with_fluid = bagnold_with_fluid(&zs);
    let top = *with_fluid.last().expect("cells in the layer");
    let dry = layer.iter().map(|&(z, u)| (u - bagnold(z)).abs()).fold(0.0, f64::max) / bagnold(H);
    let wet = layer.iter().zip(&with_fluid).map(|(&(_, u), &r)| (u - r).abs()).fold(0.0, f64::max) / top;
    (dry, wet, ending == Ending::Steady)
}

/// The layer reaches steady state at the scene's (default) settings, and the error against
/// the profile with the fluid, the exact steady solution of the model's continuous
/// equations, falls at second order: measured 0.087 % (50 cells across H),
/// 0.014 % (100), 0.0025 % (200).
#[test]
fn dry_mu_i_incline_bagnold_profile() {
    let (dry_c, coarse, steady_c) = dry_incline_error(63);
    let (dry_f, fine, steady_f) = dry_incline_error(125);
    println!(
        "dry mu(I) incline, max error / u_surface: against Bagnold {:.3} % (50 cells across H), {:.3} % (100); \
         against the profile with the fluid {:.4} %, {:.4} %",
        100.0 * dry_c,
        100.0 * dry_f,
        100.0 * coarse,
        100.0 * fine
    );
    assert!(steady_c && steady_f, "not steady");
    assert!(fine < 1e-3, "error {:.4} % at 100 cells", 100.0 * fine);
    // second order: the error divides by 4 per halving of the cell; at least 3 asked
    assert!(fine < coarse / 3.0, "not second order: {coarse} -> {fine}");
}

/// docs/verification.md, benchmark 6: the Bagnold profile within 1 % at 100 cells across the
/// layer (measured 0.64 %; the rest is the fluid, which the formula neglects: buoyancy,
/// entrained air and the stress of the air above shift I by ~0.4 %).
#[test]
fn dry_mu_i_incline_within_1_percent() {
    let (e, _, _) = dry_incline_error(125);
    assert!(e < 0.01, "error {:.2} % at 100 cells", 100.0 * e);
}

/// Chassagne et al. 2023 reference case (table 2 case 1, proposed model) against the
/// coupled fluid-DEM profile in `../shared/data/chassagne_dem_bedload_sedfoam` (this test
/// reads that file): steady state reached, sediment mass conserved to 1e-10, RMS
/// differences of phi and u_p reported, and qs* within `tolerance` of the DEM value.
fn chassagne_case01_against_dem(tolerance: f64) {
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let s = Scene::from_file(root.join("cases/chassagne2023/case01.toml")).expect("case01");
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady, "case 1 must reach steady state");
    assert!(m.mass_error() < 1e-10, "mass error {:e}", m.mass_error());
    let dem_file = root.join("../shared/data/chassagne_dem_bedload_sedfoam/BedloadTurbDEM.txt");
    let Ok(text) = std::fs::read_to_string(&dem_file) else {
        saltus_core::data::missing(&dem_file, "the comparison with the coupled DEM");
        return;
    };
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|v| v.parse().expect("number")).collect())
        .collect();
    let (d, g, sm1): (f64, f64, f64) = (6e-3, 9.81, 1.5);
    let scale = (sm1 * g * d * d * d).sqrt();
    let dem_qs: f64 =
        rows.windows(2).map(|w| 0.5 * (w[0][1] * w[0][2] + w[1][1] * w[1][2]) * (w[1][0] - w[0][0])).sum();
    let dem = dem_qs / scale;
    let qs: f64 = m.phi().iter().zip(m.u_p()).zip(m.dz()).map(|((p, u), h)| p * u * h).sum();
    let ours = qs / scale;
    let err = (ours - dem).abs() / dem;
    let interp = |f: &[f64], z: f64| {
        let zc = m.z();
        if z <= zc[0] {
            return f[0];
        }
        let j = zc.partition_point(|&c| c < z).min(zc.len() - 1);
        let t = (z - zc[j - 1]) / (zc[j] - zc[j - 1]);
        f[j - 1] * (1.0 - t) + f[j] * t
    };
    let rms_phi = (rows.iter().map(|r| (interp(m.phi(), r[0]) - r[1]).powi(2)).sum::<f64>() / rows.len() as f64).sqrt();
    let moving: Vec<&Vec<f64>> = rows.iter().filter(|r| r[1] > 1e-3).collect();
    let rms_up =
        (moving.iter().map(|r| (interp(m.u_p(), r[0]) - r[2]).powi(2)).sum::<f64>() / moving.len() as f64).sqrt();
    println!(
        "case 1: qs* = {ours:.4}, DEM {dem:.4}, error {:.1} %; RMS phi {rms_phi:.4}, RMS u_p (phi > 1e-3) {rms_up:.4} m/s",
        100.0 * err
    );
    assert!((dem - 2.337).abs() < 0.01, "DEM Qs* from the file {dem}");
    assert!(err < tolerance, "qs* = {ours}, DEM {dem}: error {:.1} % > {:.0} %", 100.0 * err, 100.0 * tolerance);
}

/// The paper's target (figure 9a): the proposed model within 15 % of the DEM transport
/// rate of case 1.
#[test]
fn chassagne_case01_against_dem_within_15_percent() {
    chassagne_case01_against_dem(0.15);
}

/// The initial (Garzo-Dufty) model of Chassagne et al. 2023 overpredicts the transport of
/// case 1 by far (paper: error over 50 %); the friction and saltation corrections are what
/// bring it within 15 %. Same scene as the proposed model except the granular table.
#[test]
fn chassagne_case01_initial_model_error_is_large() {
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let initial = r#"closures.granular={type="frictional_collisional", restitution=0.7, friction=0.4, g0={type="chialvo_sundaresan"}, restitution_model={type="plain"}, saltation={enabled=false}, drag_dissipation="linear"}"#;
    let s =
        Scene::from_file_with(root.join("cases/chassagne2023/case01.toml"), &[initial.to_string()]).expect("case01");
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let scale = (1.5f64 * 9.81 * 6e-3f64.powi(3)).sqrt();
    let qs: f64 = m.phi().iter().zip(m.u_p()).zip(m.dz()).map(|((p, u), h)| p * u * h).sum();
    let err = (qs / scale - 2.337).abs() / 2.337;
    println!("case 1, initial model: qs* = {:.4}, error {:.1} % against the DEM 2.337", qs / scale, 100.0 * err);
    assert!(err > 0.5, "initial model error {:.1} % should be large", 100.0 * err);
}

mod stress {
    use super::*;
    use proptest::prelude::*;

    fn bedload(theta: f64, r: f64, d: f64, e: f64, mu_p: f64, cells: usize) -> Scene {
        let h_w = theta * (r - 1.0) * d / 0.05;
        scene(&format!(
            "
[fluid]
density = 1000.0
viscosity = 1.0e-6
[particles]
diameter = {d}
density = {rho_p}
[physics]
slope = 0.05
[closures.drag]
type = \"dallavalle\"
[closures.hindrance]
type = \"richardson_zaki\"
exponent = 3.1
[closures.turbulence]
type = \"mixing_length\"
form = \"li_sawamoto\"
[closures.granular]
type = \"frictional_collisional\"
restitution = {e}
friction = {mu_p}
[domain]
bed_height = {bed}
water_depth = {h_w}
cells = {cells}
[solver]
type = \"eulerian\"
[solver.eulerian]
end_time = 30.0
",
            rho_p = 1000.0 * r,
            bed = 12.5 * d
        ))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

        /// Stability stress suite: any bedload scene in the stated ranges either runs with
        /// finite fields, 0 <= phi < phi_max, T >= 0 and the mass conserved, or stops
        /// cleanly naming the time, the cell and the field.
        #[test]
        fn bedload_runs_stay_physical_or_stop_cleanly(
            theta in 0.1f64..1.5,
            r in 1.2f64..4.0,
            d in 0.2e-3f64..10e-3,
            e in 0.3f64..0.95,
            mu_p in 0.0f64..1.0,
            cells in 50usize..400,
        ) {
            let s = bedload(theta, r, d, e, mu_p, cells);
            let (m, ending) = run(&s);
            if let Ending::Unstable(b) = &ending {
                prop_assert!(b.time.is_finite() && b.time >= 0.0);
                match b.place {
                    saltus_solvers::run::Place::Cell { index, .. } => prop_assert!(index < cells),
                    ref other => prop_assert!(false, "a column breakdown names a cell: {other:?}"),
                }
                prop_assert!(!b.field.is_empty() && !b.reason.is_empty());
            }
            let phi_max = 0.635;
            for i in 0..m.len() {
                let (phi, t) = (m.phi()[i], m.temperature()[i]);
                prop_assert!(phi.is_finite() && phi >= -1e-9 && phi < phi_max, "phi {} in cell {}", phi, i);
                prop_assert!(t.is_finite() && t >= 0.0, "T {} in cell {}", t, i);
                prop_assert!(m.u_f()[i].is_finite() && m.u_p()[i].is_finite());
            }
            prop_assert!(m.mass_error() < 1e-10, "mass error {:e}", m.mass_error());
        }
    }
}

/// All 19 cases of Chassagne et al. 2023 table 2 (cases/chassagne2023) reach steady state
/// from the bed at rest without intervention, conserve the sediment mass and transport
/// sediment; qs* per case is printed (`--nocapture`). Against the paper's findings
/// (section 4.2, figures 8-10): cases 1-5 differ only in the Shields number and transport
/// grows with it; for frictional grains (mu_p >= 0.4: cases 1, 12-14) and for
/// restitution e <= 0.7 at mu_p = 0.4 (cases 1, 15, 16; the dissipation "is the same for
/// e <= 0.7", figure 10) the transport no longer depends on the microscopic properties
/// (within 10 % here); frictionless grains (case 9) move far more (over twice). Case 17
/// (e = 0.9) is printed, not gated: the model gives about 18 % more than case 1.
#[test]
fn all_chassagne_cases_reach_steady_state() {
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023");
    let mut by_theta = Vec::new();
    // qs* of case k at k - 1
    let mut qs_star = Vec::with_capacity(19);
    for k in 1..=19 {
        let file = root.join(format!("case{k:02}.toml"));
        let s = Scene::from_file(&file).expect("case");
        let (m, ending) = run(&s);
        let d = s.particles.diameter;
        let scale = (s.submerged_ratio() * 9.81 * d * d * d).sqrt();
        let qs: f64 = m.phi().iter().zip(m.u_p()).zip(m.dz()).map(|((p, u), h)| p * u * h).sum();
        println!("case {k:2}: qs* = {:.4}, {} steps, t = {:.1} s", qs / scale, m.steps(), m.time());
        assert_eq!(ending, Ending::Steady, "case {k}");
        assert!(m.mass_error() < 1e-10, "case {k}: mass error {:e}", m.mass_error());
        assert!(qs > 0.0, "case {k}: no transport");
        qs_star.push(qs / scale);
        if k <= 5 {
            let theta = s.domain.water_depth * s.physics.slope / (s.submerged_ratio() * d);
            by_theta.push((theta, qs / scale));
        }
    }
    by_theta.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(by_theta.windows(2).all(|w| w[1].1 > w[0].1), "qs* must grow with theta: {by_theta:?}");
    let spread = |ks: &[usize]| {
        let v: Vec<f64> = ks.iter().map(|&k| qs_star[k - 1]).collect();
        let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        (hi - lo) / lo
    };
    assert!(spread(&[1, 12, 13, 14]) < 0.1, "mu_p >= 0.4: spread {:.3}", spread(&[1, 12, 13, 14]));
    assert!(spread(&[1, 15, 16]) < 0.1, "e = 0.3-0.7: spread {:.3}", spread(&[1, 15, 16]));
    println!("e = 0.9 (case 17) against e = 0.7 (case 1): qs* ratio {:.3}", qs_star[16] / qs_star[0]);
    assert!(qs_star[8] > 2.0 * qs_star[0], "frictionless grains: {} vs {}", qs_star[8], qs_star[0]);
}

/// Reading a run does not advance it: `derived`, `particle_pressure` and the report of
/// the stepper leave the state and the coefficients as they were (the same profiles twice,
/// bit for bit), every number of the report is finite, phi is not negative, and the
/// driver's progress counts the solver's accepted steps.
#[test]
fn reading_case01_does_not_advance_it_and_writes_finite_numbers() {
    use saltus_solvers::run::Stepper;
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let s = Scene::from_file_with(root.join("cases/chassagne2023/case01.toml"), &["domain.cells=60".to_string()])
        .expect("case01");
    let (m, ending) = run(&s);
    assert_eq!(ending, Ending::Steady);
    let before = (m.phi().to_vec(), m.u_f().to_vec(), m.eddy_viscosity().to_vec(), m.steps(), m.time());
    let (d1, p1) = (m.derived(), m.particle_pressure());
    let report = m.report(&ending, &saltus_solvers::run::Clock { wall: 1.0, flow: 1.0 });
    let (d2, p2) = (m.derived(), m.particle_pressure());
    let after = (m.phi().to_vec(), m.u_f().to_vec(), m.eddy_viscosity().to_vec(), m.steps(), m.time());
    assert_eq!(before, after);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (a, b) in [(&d1.tau_p, &d2.tau_p), (&d1.tau_f, &d2.tau_f), (&d1.p_p, &d2.p_p), (&d1.control, &d2.control)] {
        assert_eq!(bits(a), bits(b));
    }
    assert_eq!(bits(&p1), bits(&p2));
    // every value is finite but the control number where the grains carry no pressure,
    // which is undefined (NaN in memory, an empty cell in profiles.csv)
    let p_p = report.profiles.get("p_p").expect("p_p").to_vec();
    for (name, values) in &report.profiles.columns {
        for (i, v) in values.iter().enumerate() {
            let undefined = name == "control_number" && p_p[i] <= 0.0;
            assert!(v.is_finite() != undefined, "{name}[{i}] = {v} with p_p = {}", p_p[i]);
        }
    }
    let csv = report.profiles.to_csv();
    assert!(!csv.contains("NaN") && !csv.contains("inf"), "non-finite number in profiles.csv");
    let phi = &report.profiles.columns.iter().find(|c| c.0 == "phi").expect("phi").1;
    assert!(phi.iter().all(|&p| p >= 0.0));
    assert_eq!(m.progress().steps, m.steps() as u64);
    assert_eq!(report.summary.steps, m.steps());
    assert_eq!(report.summary.ending, "steady");
}

/// Case 1 (kinetic theory, granular temperature) on a grid stretched from the wall
/// (ratio 1.01 at 120 cells: the top cell 3.3 times the bottom one) reaches steady state
/// with qs* within 0.5 % of the uniform grid (measured 0.21 %): every shear rate, that of
/// the temperature production included, comes from the column operator's face values,
/// exact on a stretched grid.
#[test]
fn case01_on_a_stretched_grid_matches_the_uniform_one() {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let qs_star = |ratio: f64| {
        let s = Scene::from_file_with(&file, &[format!("domain.stretching={ratio}")]).expect("case01");
        let (m, ending) = run(&s);
        assert_eq!(ending, Ending::Steady, "ratio {ratio}");
        assert!(m.mass_error() < 1e-10);
        let d = s.particles.diameter;
        let scale = (s.submerged_ratio() * 9.81 * d * d * d).sqrt();
        m.phi().iter().zip(m.u_p()).zip(m.dz()).map(|((p, u), h)| p * u * h).sum::<f64>() / scale
    };
    let (uniform, stretched) = (qs_star(1.0), qs_star(1.01));
    assert!((stretched / uniform - 1.0).abs() < 5e-3, "qs* {stretched} against {uniform}");
}
