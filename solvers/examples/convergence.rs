//! Convergence study of the Eulerian solver on Chassagne et al. 2023 case 1: qs* and the
//! profiles at 50-800 cells and three time-step controls, against a 1600-cell reference
//! run, with wall time. Prints a markdown table (docs/performance.md).
//!
//! `cargo run --release -p saltus-solvers --example convergence`

use std::path::Path;
use std::time::Instant;

use saltus_core::scene::Scene;
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{drive, Ending, Quiet};

struct Result {
    z: Vec<f64>,
    phi: Vec<f64>,
    up: Vec<f64>,
    qs_star: f64,
    wall: f64,
    steps: usize,
    steady: bool,
}

fn solve(cells: usize, max_phi_change: f64) -> Result {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let overrides = [
        format!("domain.cells={cells}"),
        format!("solver.max_phi_change={max_phi_change}"),
        "solver.end_time=2000".into(),
    ];
    let scene = Scene::from_file_with(&file, &overrides).expect("case01");
    let cfg = Config::from_scene(&scene).expect("config");
    // best of three for the wall time
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..3 {
        let mut m = Eulerian::new(&scene, cfg.clone()).expect("solver");
        let t = Instant::now();
        let ending = drive(&mut m, &mut Quiet).ending;
        best = best.min(t.elapsed().as_secs_f64());
        let scale = (1.5f64 * 9.81 * 6e-3f64.powi(3)).sqrt();
        let qs: f64 = m.phi().iter().zip(m.u_p()).zip(m.dz()).map(|((p, u), h)| p * u * h).sum();
        out = Some(Result {
            z: m.z().to_vec(),
            phi: m.phi().to_vec(),
            up: m.u_p().to_vec(),
            qs_star: qs / scale,
            wall: 0.0,
            steps: m.steps(),
            steady: ending == Ending::Steady,
        });
    }
    let mut r = out.expect("one run");
    r.wall = best;
    r
}

fn interp(z: &[f64], f: &[f64], x: f64) -> f64 {
    if x <= z[0] {
        return f[0];
    }
    let j = z.partition_point(|&c| c < x).min(z.len() - 1);
    let t = ((x - z[j - 1]) / (z[j] - z[j - 1])).clamp(0.0, 1.0);
    f[j - 1] * (1.0 - t) + f[j] * t
}

fn main() {
    saltus_closures::link();
    let fine = solve(1600, 0.02);
    println!("reference: 1600 cells, qs* = {:.5}, {} steps, {:.3} s", fine.qs_star, fine.steps, fine.wall);
    println!();
    println!(
        "| cells | dz/d | max_phi_change | steps | steady | qs* | qs* error | L2 phi | L2 u_p (m/s) | wall time (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let rows: Vec<(usize, f64)> =
        [50, 100, 120, 200, 400, 800].iter().map(|&c| (c, 0.02)).chain([(120, 0.005), (120, 0.05)]).collect();
    for (cells, mpc) in rows {
        let r = solve(cells, mpc);
        let l2 = |f: &[f64], g: &[f64]| {
            (r.z.iter().zip(f).map(|(z, v)| (v - interp(&fine.z, g, *z)).powi(2)).sum::<f64>() / r.z.len() as f64)
                .sqrt()
        };
        println!(
            "| {cells} | {:.3} | {mpc} | {} | {} | {:.4} | {:.2} % | {:.2e} | {:.2e} | {:.4} |",
            0.183 / cells as f64 / 6e-3,
            r.steps,
            if r.steady { "yes" } else { "no" },
            r.qs_star,
            100.0 * (r.qs_star - fine.qs_star).abs() / fine.qs_star,
            l2(&r.phi, &fine.phi),
            l2(&r.up, &fine.up),
            r.wall
        );
    }
}
