//! The coupled DEM under a time-dependent forcing: a free stream U(t) = A sin(2 pi t / T)
//! drives its fluid column by -dp/dx = rho_f dU/dt (`physics.forcing`, of = "velocity").
//! Above the bed's boundary layer the shear stress has no divergence, so the fluid moves
//! with the free stream: u_f = U(t) at the symmetry plane on top, whatever the bed does,
//! to the time error of the coupling: the column is stepped by backward Euler over a fluid
//! period tau_f to the end of the period the grains then cross, so the sampled fluid leads
//! the free stream by one to two fluid periods (measured: the zero crossing 0.05 T early
//! at tau_f = T / 40). At tau_f = T / 800 the phase-averaged u_f at the top is within
//! 2.0 % of A of the bin means of U in every bin (gated at 3 %).

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_solvers::run::Quiet;

fn tmp_out(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("saltus_forced_dem_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// The column of a CSV with a header, as numbers.
fn column(text: &str, name: &str) -> Vec<f64> {
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let k = header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    lines.map(|l| l.split(',').nth(k).and_then(|v| v.parse().ok()).unwrap_or(f64::NAN)).collect()
}

#[test]
fn the_fluid_above_a_dem_bed_follows_an_oscillating_free_stream() {
    saltus_closures::link();
    let (amplitude, period) = (0.05, 0.4);
    // one and a quarter periods: the free stream is at its crest, A, at the end
    let end = 1.25 * period;
    let set: Vec<String> = [
        "solver.type=lagrangian",
        "solver.lagrangian.length=1.68e-3",
        "solver.lagrangian.width=1.68e-3",
        "domain.bed_height=1.7e-3",
        "domain.water_depth=0.03",
        "solver.lagrangian.cells=300",
        "solver.lagrangian.settle_time=0.02",
        "solver.lagrangian.threads=1",
        "solver.lagrangian.fluid_period=5e-4",
        "closures.turbulence={type=\"laminar\"}",
        "solver.lagrangian.stats_start=0",
        "output.phases=8",
        "output.spin_up_periods=0",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        format!("physics.forcing.period={period}"),
        format!("physics.forcing.amplitudes=[{amplitude}]"),
        format!("solver.lagrangian.end_time={end}"),
    ])
    .collect();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/odonoghue_wright2004/oscillatory_sheet_flow.toml");
    let s = Scene::from_file_with(file, &set).expect("scene");
    let out = tmp_out("free_stream");
    saltus_solvers::run(&s, &out, &mut Quiet).expect("runs");

    // the phase-averaged u_f at the top of the column, bin by bin, against the free
    // stream's mean over the bin: A sin(2 pi t_c / T) sin(pi / n) / (pi / n) for n bins
    let profiles = std::fs::read_to_string(out.join("phase_profiles.csv")).expect("phase_profiles.csv");
    let (phase, z, u) = (column(&profiles, "phase"), column(&profiles, "z"), column(&profiles, "u_f"));
    let centre = column(&profiles, "t_over_period");
    let top = z.iter().copied().fold(f64::MIN, f64::max);
    let bins = 8.0;
    let mean = (std::f64::consts::PI / bins).sin() / (std::f64::consts::PI / bins);
    let mut seen = 0;
    for k in 0..z.len() {
        if z[k] != top {
            continue;
        }
        let exact = amplitude * mean * (2.0 * std::f64::consts::PI * centre[k]).sin();
        println!("bin {}: u_f at the top {:.5} m/s, free stream {exact:.5} m/s", phase[k], u[k]);
        assert!((u[k] - exact).abs() < 0.03 * amplitude, "bin {}: u_f {} m/s against {exact} m/s", phase[k], u[k]);
        seen += 1;
    }
    assert_eq!(seen, 8, "{profiles}");
    // the bed holds the fluid at rest at its bottom
    let bottom = z.iter().copied().fold(f64::MAX, f64::min);
    for k in (0..z.len()).filter(|&k| z[k] == bottom) {
        assert!(u[k].abs() < 0.05 * amplitude, "u_f at the bottom {} m/s", u[k]);
    }

    // one whole period binned: the forcing column is the free stream at the bins' centres
    let phases = std::fs::read_to_string(out.join("phases.csv")).expect("phases.csv");
    let (t, forcing) = (column(&phases, "t_over_period"), column(&phases, "forcing"));
    assert_eq!(t.len(), 8, "{phases}");
    for (tk, fk) in t.iter().zip(&forcing) {
        let exact = amplitude * (2.0 * std::f64::consts::PI * tk).sin();
        assert!((fk - exact).abs() < 1e-9, "forcing {fk} at t/T = {tk}, U = {exact}");
    }
    let _ = std::fs::remove_dir_all(&out);
}
