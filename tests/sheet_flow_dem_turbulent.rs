//! Cheng, Chauchat, Hsu & Calantoni's sheet flow (case MB) in the coupled DEM with the
//! two-phase low-Re k-omega of their table 1 (C_s = 1, C_3w = 0.14, C_4w = 0, C_t = 1/6),
//! the drag damping of eq 24 (the relative velocity time-averaged from t_0 = 5 s) and the
//! eddy interaction model (C0 = 3) stays turbulent: 4 s continued from its developed state
//! at 100.5 s of flow, `tests/fixtures/mb_dem_developed/checkpoint.bin`.
//!
//! The scene is `cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml` as shipped but
//! for its window; `tests/fixtures/mb_dem_developed/README.md` gives the command that writes
//! the fixture (about 600 CPU-s), to be run again when the checkpoint format or the scene
//! changes (the restart then refuses the fixture, naming why). Where the coupling damps the
//! fluid's turbulence too strongly (the grains' exchange coefficient instead of eq 24's beta,
//! docs/notes/k_omega_dem_coupling.md) the sheet laminarises: the Reynolds stress leaves
//! its lowest millimetres and falls to about half the bed shear stress above it, and the
//! column accelerates. Checked over 100.5-104.5 s (about 15 CPU-s): the fluid's and the
//! grains' stresses carry the driving pressure gradient (momentum balance of the mixture),
//! the fluid's stress is Reynolds stress from 2 mm above the sheet's top, and the transport
//! rate is Cheng's within what a 4 s window of a 10 d x 10 d cell scatters.

mod common;

use std::path::Path;

use common::{cell, read_table, saltus, stderr, summary, tmp_dir};

const SCENE: &str = "cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml";
const FIXTURE: &str = "tests/fixtures/mb_dem_developed";
/// driving gradient G (Pa/m), rho_f u*^2 / h with u* = 5 cm/s and h = 0.128 m
const G: f64 = 19.53125;
const RHO_F: f64 = 1000.0;
/// u*^2 = G h / rho_f (m^2/s^2)
const U_STAR2: f64 = G * 0.128 / RHO_F;

struct Profiles {
    z: Vec<f64>,
    phi: Vec<f64>,
    tau_t: Vec<f64>,
    tau_f: Vec<f64>,
    tau_p: Vec<f64>,
}

fn profiles(dir: &Path) -> Profiles {
    let (h, rows) = read_table(&dir.join("profiles.csv"));
    let col = |name: &str| -> Vec<f64> { rows.iter().map(|r| cell(&h, r, name).parse::<f64>().unwrap()).collect() };
    // the grains' stress is left blank in cells no grain reaches: no stress there
    let tau_p = rows.iter().map(|r| cell(&h, r, "tau_p").parse::<f64>().unwrap_or(0.0)).collect();
    Profiles { z: col("z"), phi: col("phi"), tau_t: col("tau_t"), tau_f: col("tau_f"), tau_p }
}

/// Value of `v` at height `z` (linear between the two profile points around it).
fn at(p: &Profiles, v: &[f64], z: f64) -> f64 {
    let k = p.z.iter().position(|&zk| zk >= z).expect("height inside the column");
    let (z0, z1) = (p.z[k - 1], p.z[k]);
    v[k - 1] + (v[k] - v[k - 1]) * (z - z0) / (z1 - z0)
}

#[test]
fn the_dem_sheet_with_table_1_and_eq_24_stays_turbulent_over_its_developed_state() {
    let out = tmp_dir("mb_dem_turbulent");
    let o = saltus(&[
        "run",
        SCENE,
        "--restart",
        FIXTURE,
        "--out",
        out.to_str().unwrap(),
        "--set",
        "solver.lagrangian.end_time=104.5",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = summary(&out);
    let p = profiles(&out);

    // the sheet's top: the highest level where phi >= 0.3 (bed-aligned, as the data)
    let k_top = (0..p.z.len()).rev().find(|&k| p.phi[k] >= 0.3).expect("a sheet");
    let z_s = p.z[k_top];
    // the free-slip top of the column
    let z_top = *p.z.last().unwrap();
    let tau_0 = RHO_F * U_STAR2;

    // Momentum balance of the mixture: the fluid's shear stress (Reynolds and viscous) and
    // the grains' carry the driving gradient, G (z_top - z), from the bed through the sheet
    // to the clear water. The column still gains speed slowly at 100 s (the Shields number
    // of the bed shear climbs 0.386, 0.398, 0.403 over 70-100 s towards u*'s 0.4425), so
    // the stresses carry 0.88-0.98 of it; a column laminarising and accelerating carries less.
    for dz in [-0.002, 0.0, 0.002, 0.005, 0.02, 0.04] {
        let z = z_s + dz;
        let tau = at(&p, &p.tau_f, z) + at(&p, &p.tau_p, z);
        let ratio = tau / (G * (z_top - z));
        assert!(
            (0.8..1.05).contains(&ratio),
            "fluid and grain shear stress {tau:.3} Pa at {:+.0} mm from the sheet's top: {ratio:.3} of G (z_top - z)",
            dz * 1e3
        );
    }
    // The turbulence reaches into the sheet: 2 mm above phi = 0.3 (phi about 0.2) the
    // fluid's stress is Reynolds stress for 0.89 of it; where the drag damping laminarises
    // the sheet, its lowest 3 mm carry almost none (docs/notes/k_omega_dem_coupling.md).
    let share = at(&p, &p.tau_t, z_s + 0.002) / at(&p, &p.tau_f, z_s + 0.002);
    assert!(share > 0.7, "Reynolds share {share:.3} of the fluid's stress 2 mm above the sheet");
    // Above it the Reynolds stress is 0.77-0.83 rho_f u*^2 7-20 mm up (the data about 0.9;
    // 0.5-0.55 where the coupling damped it with the grains' exchange coefficient).
    for dz in [0.007, 0.01, 0.02] {
        let r = at(&p, &p.tau_t, z_s + dz) / tau_0;
        assert!(r > 0.65, "Reynolds stress {r:.3} rho_f u*^2 at {:.0} mm above the sheet", dz * 1e3);
    }

    // qs* against Cheng's 1.89 (table 4, theta 0.5): the sheet gives 1.82 +- 0.03 over
    // 100-150 s and 1.70 over this window; 4 s windows of it scatter by some 10 %.
    let q = s["qs_star"].as_f64().unwrap();
    assert!((q - 1.89).abs() < 0.3 * 1.89, "qs* {q} over the window, Cheng 1.89");
}
