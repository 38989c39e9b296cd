//! The DEM's granular fields (solvers/src/lagrangian/granular.rs) proven by the momentum
//! balance of the particle phase, in a coupled bed, a dry layer on an incline and a
//! static packing.
//!
//! The time-averaged momentum balance of the grains of a slice, steady and uniform in
//! x and y (Chassagne et al. 2023 eq 2.2 for the particle phase; Maurin et al. 2015
//! eqs 1, 9-11 and 14 for the forces of this DEM), with P the compressive-positive stress
//! of the fields (kinetic plus contact, P = 0 above the grains):
//!
//! ```text
//! dP_xz/dz = rho_p phi_m b_x + n<f_Dx>,   dP_zz/dz = rho_p phi_m b_z + n<f_Dz>
//! => tau_p(z) = -P_xz(z) = int_z^top [rho_p phi_m b_x + n<f_Dx>] dz'
//!    p_p(z)   =  P_zz(z) = int_z^top [(rho_p - rho_f) g cos(alpha) phi_m - n<f_Dz>] dz'
//! ```
//!
//! b is the body acceleration of the mobile grains: b_x = g sin(alpha) (the fluid's
//! pressure is hydrostatic in z only, so the grains feel their whole weight along the
//! slope; a pressure gradient would add dp/dx / rho_p), b_z = -(1 - rho_f/rho_p) g
//! cos(alpha) (weight and buoyancy); n<f_D> is the drag of the fluid on the mobile grains
//! per unit volume (measured, field `drag` of the averages). Dry: rho_f = 0, no drag. The
//! integrals are taken over the slices above, with half of the slice itself (the slice
//! average of the stress). phi_m is the volume fraction of the mobile grains: the
//! comparison stops where the fixed grains of the rough bottom reach.

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::granular::GranularAverages;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::{drive, Ending, Quiet, Stepper};

fn scene(name: &str, set: &[&str]) -> Scene {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases").join(name);
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Scene::from_file_with(&file, &set).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Run `s` to its end time; the solver with its averages and profiles.
fn run(s: &Scene) -> (Lagrangian<'_>, GranularAverages, saltus_solvers::output::Profiles) {
    let cfg = Config::from_scene(s).expect("config");
    let mut m = Lagrangian::new(s, cfg).expect("solver");
    let (ending, _) = drive(&mut m, &mut Quiet);
    assert_eq!(ending, Ending::EndTime);
    let g = m.granular_averages().expect("granular fields");
    let profiles = m.report(&ending, 0.0).profiles;
    (m, g, profiles)
}

/// Height above the column base below which the fixed grains reach (m).
fn fixed_top(m: &Lagrangian<'_>) -> f64 {
    let p = m.particles();
    let base = m.slices().base;
    (p.n_mobile..p.len()).map(|a| p.z[a] + p.radius[a] - base).fold(0.0, f64::max)
}

/// int_z^top f dz' at each slice (slice average: half of the slice's own share).
fn from_top(f: &[f64], dz: f64) -> Vec<f64> {
    let mut out = vec![0.0; f.len()];
    let mut above = 0.0;
    for c in (0..f.len()).rev() {
        // no grains, no force (the drag is undefined there)
        let f = if f[c].is_finite() { f[c] } else { 0.0 };
        out[c] = above + 0.5 * f * dz;
        above += f * dz;
    }
    out
}

/// Largest |measured / expected - 1| over the slices with phi > 0.1 above `z_min`, with
/// the slice where it occurs; printed with the profile.
fn worst(label: &str, z: &[f64], phi: &[f64], measured: &[f64], expected: &[f64], z_min: f64) -> (f64, f64) {
    let mut w = (0.0, f64::NAN);
    for c in 0..z.len() {
        if phi[c] > 0.1 && z[c] > z_min {
            let e = (measured[c] / expected[c] - 1.0).abs();
            if !(e <= w.0) {
                w = (e, z[c]);
            }
        }
    }
    eprintln!("{label}: largest relative error {:.4} at z = {:.5} m (phi > 0.1, z > {z_min:.5} m)", w.0, w.1);
    w
}

fn column<'p>(p: &'p saltus_solvers::output::Profiles, name: &str) -> &'p [f64] {
    p.get(name).unwrap_or_else(|| panic!("no column {name}"))
}

/// The two balances of a run: (p_p error, tau_p error), each the largest relative error
/// and where.
fn balances(s: &Scene, label: &str) -> ((f64, f64), (f64, f64)) {
    let (m, g, p) = run(s);
    let (z, phi) = (column(&p, "z"), column(&p, "phi"));
    let dz = m.dz();
    let rho_p = s.particles.density;
    let wet = s.solver.lagrangian.fluid != saltus_core::scene::FluidMode::Off;
    let rho_f = if wet { s.fluid.density } else { 0.0 };
    let sin = s.physics.slope;
    let cos = (1.0 - sin * sin).sqrt();
    let gr = s.physics.gravity;
    let bx = gr * sin + if wet { s.physics.pressure_gradient / rho_p } else { 0.0 };
    let fz: Vec<f64> = (0..z.len()).map(|c| (rho_p - rho_f) * gr * cos * phi[c] - g.drag[2][c]).collect();
    let fx: Vec<f64> = (0..z.len()).map(|c| rho_p * bx * phi[c] + g.drag[0][c]).collect();
    let (pz, tx) = (from_top(&fz, dz), from_top(&fx, dz));
    let z_min = fixed_top(&m);
    for c in 0..z.len() {
        if phi[c] > 0.05 {
            eprintln!(
                "{label} z {:.5} phi {:.3} p_p {:.4} ({:.4} kin) expected {:.4} | tau_p {:.4} ({:.4} kin) expected {:.4} | drag x {:.3} z {:.3}",
                z[c], phi[c], g.p_p[0][c], g.p_p[1][c], pz[c], g.tau_p[0][c], g.tau_p[1][c], tx[c], g.drag[0][c], g.drag[2][c]
            );
        }
    }
    let ep = worst(&format!("{label} p_p"), z, phi, &g.p_p[0], &pz, z_min);
    let et = worst(&format!("{label} tau_p"), z, phi, &g.tau_p[0], &tx, z_min);
    (ep, et)
}

/// A coupled bed of 10 d x 10 d x 6 d (about 700 mobile grains of case 1), theta about 0.17.
fn coupled_bed(set: &[&str]) -> Scene {
    let mut all = vec![
        "solver.type=lagrangian",
        "closures.turbulence={type=\"mixing_length\", form=\"li_sawamoto\", phi_max=0.61}",
        "solver.lagrangian.length=0.06",
        "solver.lagrangian.width=0.06",
        "domain.bed_height=0.036",
        "domain.water_depth=0.03",
        "solver.lagrangian.cells=120",
        "solver.lagrangian.settle_time=0.1",
    ];
    all.extend_from_slice(set);
    scene("chassagne2023/case01.toml", &all)
}

#[test]
fn coupled_bed_stresses_balance_the_buoyant_weight_and_the_driving() {
    let s = coupled_bed(&["solver.lagrangian.stats_start=0.5", "solver.lagrangian.end_time=1.5"]);
    let ((ep, _), (et, _)) = balances(&s, "coupled");
    assert!(ep < 0.03 && et < 0.03, "{ep} {et}");
}
