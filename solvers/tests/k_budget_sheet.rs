//! The k budget of Cheng, Chauchat, Hsu & Calantoni's eq 21 in the sheet of a DEM run's
//! final state (docs/notes/cheng_eim_effect.md): production eps nu_t S^2, dissipation
//! C_mu* k omega, drag damping 2 beta (1 - lambda) phi k / (rho_f eps), buoyancy
//! -(1/eps)(nu_t/sigma_c)(s - 1) g dphi/dz and diffusion d/dz[(nu + nu_t/sigma_k) dk/dz],
//! each written out from table 1 as `k_omega_dem_coupling.rs` holds them against the
//! closure's terms, from the column's k, omega, shear rate and eq 23 beta and the fluid's
//! phi of the checkpoint. Not in CI (it needs the runs' checkpoints):
//!
//! ```sh
//! SALTUS_K_BUDGET_RUNS=/work/runs-cheng/base_eim,/work/runs-cheng/base_none \
//!   cargo test --release -p saltus-solvers --test k_budget_sheet -- --ignored --nocapture
//! ```
//!
//! For each run it prints the terms integrated over the sheet (the cells of the fluid's phi
//! between 0.08 and 0.5) over u*^3, and their profile.

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::checkpoint;
use saltus_solvers::run::Stepper;

const NU: f64 = 1e-6;
const RHO_F: f64 = 1000.0;
/// u* of case MB (m/s)
const U_STAR: f64 = 0.05;

// table 1 (C_s = 1, C_t = 1/6, sigma_c = 1, sigma_k = 2)
const ALPHA_STAR_0: f64 = 0.024;
const RE_K: f64 = 6.0;
const RE_BETA: f64 = 8.0;
const C_MU: f64 = 0.09;
const C_S: f64 = 1.0;
const C_T: f64 = 1.0 / 6.0;
const SIGMA_C: f64 = 1.0;
const SIGMA_K: f64 = 2.0;

/// eq 21's terms per cell (m^2/s^3): production, dissipation, drag damping, buoyancy,
/// diffusion, and the face fluxes of the diffusion (m^3/s^3, n + 1 faces, 0 at both ends).
struct Budget {
    z: Vec<f64>,
    phi: Vec<f64>,
    terms: [Vec<f64>; 5],
    flux: Vec<f64>,
    dz: f64,
}

fn budget(m: &Lagrangian<'_>) -> Budget {
    let col = m.column().expect("coupled");
    let (k, w) = col.k_omega().expect("k-omega");
    let beta = col.damping_drag().expect("k-omega state");
    let shear = col.shear_rate();
    let phi = m.volume_fraction();
    let n = m.cells();
    let z = col.grid().centres().to_vec();
    let dz = m.dz();
    let s_m1 = m.material().rho_p / RHO_F - 1.0;
    let g = m.scene().physics.gravity;
    let rho_p = m.material().rho_p;
    let nu_t: Vec<f64> = (0..n)
        .map(|c| {
            let kc = k[c].max(0.0);
            let re_t = kc / (NU * w[c]);
            let a_star = (ALPHA_STAR_0 + re_t / RE_K) / (1.0 + re_t / RE_K); // eq 28
            a_star * kc / w[c] // eq 29
        })
        .collect();
    let mut terms = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for c in 0..n {
        let (kc, wc, ph) = (k[c].max(0.0), w[c], phi[c]);
        let eps = 1.0 - ph;
        let re_t = kc / (NU * wc);
        let r4 = (re_t / RE_BETA).powi(4);
        let c_mu_star = C_MU * (4.0 / 15.0 + r4) / (1.0 + r4); // eq 22
        let b = beta[c];
        let st = if b > 0.0 { rho_p / b / (C_T / (C_MU * wc)) } else { f64::INFINITY };
        let lambda = (-C_S * st).exp(); // eq 25
        let (l, r) = (c.saturating_sub(1), (c + 1).min(n - 1));
        let dphidz = (phi[r] - phi[l]) / (z[r] - z[l]);
        terms[0][c] = eps * nu_t[c] * shear[c] * shear[c];
        terms[1][c] = c_mu_star * kc * wc;
        terms[2][c] = 2.0 * b * (1.0 - lambda) * ph * kc / (RHO_F * eps);
        terms[3][c] = nu_t[c] / (eps * SIGMA_C) * s_m1 * g * dphidz;
    }
    // diffusion: fluxes through the faces with the mean of the cells' diffusivities
    let mut flux = vec![0.0; n + 1];
    for f in 1..n {
        let diff = 0.5 * ((NU + nu_t[f - 1] / SIGMA_K) + (NU + nu_t[f] / SIGMA_K));
        flux[f] = diff * (k[f] - k[f - 1]) / dz;
    }
    for c in 0..n {
        terms[4][c] = (flux[c + 1] - flux[c]) / dz;
    }
    Budget { z, phi: phi.to_vec(), terms, flux, dz }
}

#[test]
#[ignore = "reads the checkpoints of long DEM runs (SALTUS_K_BUDGET_RUNS)"]
fn the_k_budget_of_the_sheet_in_each_run() {
    saltus_closures::link();
    let runs = std::env::var("SALTUS_K_BUDGET_RUNS").expect("SALTUS_K_BUDGET_RUNS: run folders, comma-separated");
    for dir in runs.split(',') {
        let dir = Path::new(dir);
        let restart = checkpoint::read(dir).expect("checkpoint");
        let scene = Scene::from_file(dir.join("scene.toml")).expect("scene");
        let cfg = Config::from_scene(&scene).expect("config");
        let mut m = Lagrangian::new(&scene, cfg).expect("solver");
        m.restore(&restart.state).expect("restore");
        let b = budget(&m);
        let n = b.z.len();
        // the diffusion conserves k: its column integral is the flux through the ends (0)
        let total: f64 = b.terms[4].iter().sum::<f64>() * b.dz;
        let scale: f64 = b.terms[4].iter().map(|x| x.abs()).sum::<f64>() * b.dz + 1e-300;
        assert!(total.abs() <= 1e-9 * scale, "diffusion not conservative: {total} of {scale}");
        for t in &b.terms {
            assert!(t.iter().all(|x| x.is_finite()), "a term not finite");
        }
        assert!(b.terms[1].iter().chain(&b.terms[2]).all(|&x| x >= 0.0), "a sink of negative sign");
        let sheet: Vec<usize> = (0..n).filter(|&c| b.phi[c] >= 0.08 && b.phi[c] <= 0.5).collect();
        assert!(!sheet.is_empty(), "no sheet in {}", dir.display());
        let u3 = U_STAR.powi(3);
        let int = |t: &[f64]| sheet.iter().map(|&c| t[c]).sum::<f64>() * b.dz / u3;
        let (lo, hi) = (sheet[0], *sheet.last().unwrap());
        println!(
            "{}: t = {:.1} s, sheet {:.1}-{:.1} mm ({} cells) | over u*^3: production {:.3}, dissipation {:.3}, drag damping {:.3}, buoyancy {:.3}, diffusion {:.3} (flux in at the top {:.3}, out at the bottom {:.3})",
            dir.display(),
            m.time(),
            b.z[lo] * 1e3,
            b.z[hi] * 1e3,
            sheet.len(),
            int(&b.terms[0]),
            int(&b.terms[1]),
            int(&b.terms[2]),
            int(&b.terms[3]),
            int(&b.terms[4]),
            b.flux[hi + 1] / u3,
            b.flux[lo] / u3,
        );
        println!("  z(mm)  phi    | P         eps_k     drag      buoy      diff   (m^2/s^3)");
        let step = (sheet.len() / 8).max(1);
        for &c in sheet.iter().step_by(step) {
            println!(
                "  {:6.2} {:5.3} | {:9.2e} {:9.2e} {:9.2e} {:9.2e} {:9.2e}",
                b.z[c] * 1e3,
                b.phi[c],
                b.terms[0][c],
                b.terms[1][c],
                b.terms[2][c],
                b.terms[3][c],
                b.terms[4][c]
            );
        }
    }
}
