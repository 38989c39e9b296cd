//! Stokes's second problem: the laminar oscillatory boundary layer under a free stream
//! U(t) = U0 sin(omega t), driven by -dp/dx = rho_f dU/dt (docs/verification.md, the
//! Stokes layer). Exact solution (Schlichting & Gersten, Boundary-Layer Theory, 2017,
//! section 15.2; Batchelor 1967 section 4.3):
//!
//!   u(z, t) = U0 [sin(omega t) - exp(-z/delta) sin(omega t - z/delta)],
//!   delta = sqrt(2 nu / omega).
//!
//! Checked in the clear-fluid column (BDF2 step of [`FluidColumn::step_bdf2`]) and in the
//! two-fluid solver without grains (`solver.eulerian.time_stepping = "accurate"`), both
//! started from the exact solution at t = 0: the error after two periods is below 1e-4 of
//! U0 and the temporal order of BDF2, from the errors at dt, dt/2 and dt/4 against a run
//! at dt/64 on the same grid, is 2 within 0.2 (backward Euler's is 1 within 0.2). The
//! shipped scene `cases/verification/stokes_layer.toml`, run as a user runs it, writes
//! phase averages that meet the exact solution's bin means to 1e-4 of U0 and converge at
//! second order in the step.

mod common;
use common::{turbulence, viscosity};

use std::f64::consts::TAU;
use std::path::Path;

use saltus_core::scene::{parse_table, Scene};
use saltus_solvers::column::{Closures, ColumnParams, Coupling, FluidColumn, Grid, TopBoundary};
use saltus_solvers::eulerian::{Config, Eulerian};
use saltus_solvers::run::{Ending, Stepper};

const NU: f64 = 1e-6;
const PERIOD: f64 = 1.0;
const U0: f64 = 0.1;
/// Column height in Stokes thicknesses: exp(-15) = 3e-7 of U0 at the zero-stress top.
const HEIGHTS: f64 = 15.0;
const CELLS: usize = 600;

fn delta() -> f64 {
    (2.0 * NU / (TAU / PERIOD)).sqrt()
}

fn exact(z: f64, t: f64) -> f64 {
    let (w, eta) = (TAU / PERIOD, z / delta());
    U0 * ((w * t).sin() - (-eta).exp() * (w * t - eta).sin())
}

/// The clear-fluid column over two periods at `steps` per period: its velocity at 2 T.
fn column(steps: usize, bdf2: bool) -> (Vec<f64>, Vec<f64>) {
    let lam = turbulence("type = \"laminar\"");
    let clear = viscosity("type = \"clear_fluid\"");
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: None };
    let grid = Grid::uniform(CELLS, HEIGHTS * delta()).unwrap();
    let params = ColumnParams { viscosity: NU, top: TopBoundary::FreeSurface, ..ColumnParams::default() };
    let mut col = FluidColumn::new(grid, params).unwrap();
    let z = col.grid().centres().to_vec();
    let u0: Vec<f64> = z.iter().map(|&z| exact(z, 0.0)).collect();
    col.set_velocity(&u0).unwrap();
    let zeros = vec![0.0; CELLS];
    let coupling = Coupling { phi: &zeros, beta: &zeros, u_p: &zeros };
    let dt = PERIOD / steps as f64;
    let w = TAU / PERIOD;
    for k in 0..2 * steps {
        // -dp/dx = rho_f dU/dt at the end of the step (both schemes are implicit)
        let t1 = (k + 1) as f64 * dt;
        col.set_pressure_gradient(1000.0 * U0 * w * (w * t1).cos()).unwrap();
        if bdf2 {
            col.step_bdf2(dt, &coupling, &closures).unwrap();
        } else {
            col.step(dt, &coupling, &closures).unwrap();
        }
    }
    (z, col.velocity().to_vec())
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / U0
}

fn against_exact(z: &[f64], u: &[f64], t: f64) -> f64 {
    z.iter().zip(u).map(|(&z, &u)| (u - exact(z, t)).abs()).fold(0.0, f64::max) / U0
}

/// log2 of successive error ratios at dt, dt/2, dt/4.
fn orders(e: &[f64; 3]) -> [f64; 2] {
    [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()]
}

#[test]
fn stokes_layer_in_the_fluid_column() {
    let (z, u) = column(1000, true);
    let err = against_exact(&z, &u, 2.0 * PERIOD);
    println!("fluid column, BDF2 at T/1000, {CELLS} cells over {HEIGHTS} delta: max |u - exact| / U0 = {err:.2e}");
    assert!(err < 1e-4, "{err:e}");
}

#[test]
fn temporal_order_of_the_fluid_column() {
    for (bdf2, order) in [(true, 2.0), (false, 1.0)] {
        let (_, reference) = column(40 * 64, bdf2);
        let e = [40, 80, 160].map(|n| max_diff(&column(n, bdf2).1, &reference));
        let p = orders(&e);
        println!(
            "fluid column, {}: errors {e:?} at T/40, T/80, T/160; orders {p:.3?}",
            if bdf2 { "BDF2" } else { "backward Euler" }
        );
        for q in p {
            assert!((q - order).abs() < 0.2, "order {q} not {order} (errors {e:?})");
        }
    }
}

/// The two-fluid scene of the Stokes layer without grains.
fn two_fluid(steps: usize) -> Scene {
    saltus_closures::link();
    let text = format!(
        r#"
[fluid]
density = 1000.0
viscosity = {NU:e}
[particles]
diameter = 1.0e-3
density = 2650.0
[physics]
[physics.forcing]
of = "velocity"
type = "sinusoids"
period = {PERIOD}
amplitudes = [{U0}]
[domain]
bed_height = 0.0
suspension_phi = 0.0
water_depth = {h:e}
cells = {CELLS}
[solver]
type = "eulerian"
[solver.eulerian]
time_stepping = "accurate"
dt_initial = {dt:e}
dt_max = {dt:e}
end_time = {end}
[closures.turbulence]
type = "laminar"
[closures.granular]
type = "mu_i"
"#,
        h = HEIGHTS * delta(),
        dt = PERIOD / steps as f64,
        end = 2.0 * PERIOD,
    );
    let t = parse_table(&text, Path::new("stokes.toml")).expect("toml");
    Scene::from_table(t, Path::new("stokes.toml")).expect("scene")
}

/// The two-fluid solver over two periods: (z, u_f at 2 T, the largest error against the
/// exact solution over the second period, accepted steps).
fn run_two_fluid(steps: usize) -> (Vec<f64>, Vec<f64>, f64, usize) {
    let s = two_fluid(steps);
    let cfg = Config::from_scene(&s).expect("config");
    let mut m = Eulerian::new(&s, cfg).expect("solver");
    let z = m.z().to_vec();
    let u0: Vec<f64> = z.iter().map(|&z| exact(z, 0.0)).collect();
    m.set_velocities(&u0, &u0).expect("velocities");
    let mut worst: f64 = 0.0;
    let ending = loop {
        let e = m.step_unit();
        if m.time() >= PERIOD {
            worst = worst.max(against_exact(&z, m.u_f(), m.time()));
        }
        if let Some(e) = e {
            break e;
        }
    };
    assert_eq!(ending, Ending::EndTime);
    assert!((m.time() - 2.0 * PERIOD).abs() < 1e-9, "{}", m.time());
    (z, m.u_f().to_vec(), worst, m.steps())
}

#[test]
fn stokes_layer_in_the_two_fluid_solver_without_grains() {
    let (_, _, worst, steps) = run_two_fluid(1000);
    println!("two-fluid solver, BDF2 at T/1000 ({steps} steps), {CELLS} cells: max |u_f - exact| / U0 over the second period = {worst:.2e}");
    assert_eq!(steps, 2000);
    assert!(worst < 1e-4, "{worst:e}");
}

#[test]
fn temporal_order_of_the_two_fluid_solver() {
    let reference = run_two_fluid(40 * 64).1;
    let e = [40, 80, 160].map(|n| max_diff(&run_two_fluid(n).1, &reference));
    let p = orders(&e);
    println!("two-fluid solver, BDF2: errors {e:?} at T/40, T/80, T/160; orders {p:.3?}");
    for q in p {
        assert!((q - 2.0).abs() < 0.2, "order {q} (errors {e:?})");
    }
}

/// A time-dependent forcing with the steady stepping is refused at the key that fixes it.
#[test]
fn a_forcing_needs_the_time_accurate_stepping() {
    saltus_closures::link();
    let s = two_fluid(100);
    let text = s.to_toml().unwrap().replace("time_stepping = \"accurate\"", "time_stepping = \"steady\"");
    let t = parse_table(&text, Path::new("stokes.toml")).expect("toml");
    let e = Scene::from_table(t, Path::new("stokes.toml")).expect_err("refused").to_string();
    assert!(e.contains("solver.eulerian.time_stepping") && e.contains("stokes.toml"), "{e}");
}

/// The scene of the Stokes layer with one key's text replaced: the error it loads with.
fn refused(from: &str, to: &str) -> String {
    refused_all(&[(from, to)])
}

/// [`refused`] with several replacements.
fn refused_all(changes: &[(&str, &str)]) -> String {
    let mut text = two_fluid(100).to_toml().unwrap();
    for (from, to) in changes {
        assert!(text.contains(from), "{from} not in the resolved scene");
        text = text.replacen(from, to, 1);
    }
    let t = parse_table(&text, Path::new("stokes.toml")).expect("toml");
    match Scene::from_table(t, Path::new("stokes.toml")) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted with {changes:?}"),
    }
}

/// The resolved scene prints the forcing; bad combinations are refused at their key.
#[test]
fn forcing_combinations_are_checked_at_load() {
    let text = two_fluid(100).to_toml().unwrap();
    assert!(text.contains("[physics.forcing]") && text.contains("type = \"sinusoids\""), "{text}");
    let e = refused("type = \"sinusoids\"", "type = \"square\"");
    assert!(e.contains("physics.forcing") && e.contains("square"), "{e}");
    let e = refused("[physics.forcing]", "[physics.forcing]\nbogus = 1");
    assert!(e.contains("physics.forcing") && e.contains("bogus"), "{e}");
    let e = refused_all(&[
        ("slope = 0.0\n", ""),
        ("pressure_gradient = 0.0", "pressure_gradient = 0.0\nshields = 0.5\ndrive = \"slope\""),
    ]);
    assert!(e.contains("physics.forcing") && e.contains("shields"), "{e}");
    let e = refused("[output]", "[output]\nphases = 8\nspin_up_periods = 2");
    assert!(e.contains("output.spin_up_periods"), "{e}");
    let e = refused_all(&[
        ("type = \"eulerian\"", "type = \"lagrangian\""),
        ("stop_when_steady = false", "stop_when_steady = true"),
    ]);
    assert!(e.contains("solver.lagrangian.stop_when_steady"), "{e}");
    let e = refused_all(&[
        ("[output]", "[output]\nphases = 8"),
        ("type = \"sinusoids\"\nperiod = 1.0\nmean = 0.0\namplitudes = [0.1]", "type = \"constant\"\nvalue = 1.0"),
    ]);
    assert!(e.contains("output.phases"), "{e}");
}

/// The largest difference (over U0) between `phase_profiles.csv` in `out` and the exact
/// solution's mean over each phase bin: the mean of sin(omega t + c) over [t0, t1] is
/// (cos(omega t0 + c) - cos(omega t1 + c)) / (omega (t1 - t0)), the sinc factor of the bin.
fn phase_error(out: &Path) -> f64 {
    let text = std::fs::read_to_string(out.join("phase_profiles.csv")).expect("phase_profiles.csv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (ib, iz, iu) = (col("phase"), col("z"), col("u_f"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap_or(f64::NAN)).collect()).collect();
    let bins = rows.iter().map(|r| r[ib] as usize).max().expect("rows") + 1;
    assert_eq!(rows.len(), bins * CELLS, "a block of {CELLS} rows per bin");
    let w = TAU / PERIOD;
    rows.iter()
        .map(|r| {
            let (b, z, u) = (r[ib], r[iz], r[iu]);
            let (t0, t1) = (b * PERIOD / bins as f64, (b + 1.0) * PERIOD / bins as f64);
            let mean = |c: f64| ((w * t0 + c).cos() - (w * t1 + c).cos()) / (w * (t1 - t0));
            let eta = z / delta();
            let exact = U0 * (mean(0.0) - (-eta).exp() * mean(-eta));
            (u - exact).abs() / U0
        })
        .fold(0.0, f64::max)
}

/// `cases/verification/stokes_layer.toml` run as shipped (with `set`; from rest without
/// its initial profiles when `rest`), its phase error.
fn shipped(name: &str, set: &[String], rest: bool) -> f64 {
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/verification/stokes_layer.toml");
    let mut t = parse_table(&std::fs::read_to_string(&file).expect("the shipped scene"), &file).expect("toml");
    for o in set {
        saltus_core::scene::apply_override(&mut t, o).expect("override");
    }
    if rest {
        let domain = t.get_mut("domain").and_then(|d| d.as_table_mut()).expect("[domain]");
        assert!(domain.remove("initial_profiles").is_some(), "the shipped scene starts from profiles");
    }
    let scene = Scene::from_table(t, &file).expect("the shipped scene");
    let out = std::env::temp_dir().join(format!("saltus-stokes-{name}-{}", std::process::id()));
    let outcome = saltus_solvers::run(&scene, &out, &mut saltus_solvers::run::Quiet).expect("run");
    assert_eq!(outcome.ending, Ending::EndTime);
    let e = phase_error(&out);
    let _ = std::fs::remove_dir_all(&out);
    e
}

/// As shipped (started from the exact solution at t = 0, BDF2 at T/1000, 16 phase bins
/// over two periods after two of spin-up), `phase_profiles.csv` is the exact bin means to
/// 1e-4 of U0; started from rest it carries the column's slow start-up transient, above
/// 1e-2 of U0.
#[test]
fn the_shipped_stokes_scene_meets_the_exact_bin_means() {
    let e = shipped("as_shipped", &[], false);
    assert!(e < 1e-4, "phase averages {e:e} U0 from the exact bin means");
    let from_rest = shipped("from_rest", &[], true);
    assert!(from_rest > 1e-2, "from rest: {from_rest:e} U0");
}

/// The phase averages of the shipped scene converge at second order in the step, as the
/// solver does: errors at T/50, T/100 and T/200 against the exact bin means.
#[test]
fn phase_averages_of_the_shipped_scene_are_second_order_in_the_step() {
    let e: Vec<f64> = [50, 100, 200]
        .iter()
        .map(|n| {
            let dt = PERIOD / *n as f64;
            shipped(
                &format!("dt{n}"),
                &[format!("solver.eulerian.dt_initial={dt:e}"), format!("solver.eulerian.dt_max={dt:e}")],
                false,
            )
        })
        .collect();
    for w in e.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((order - 2.0).abs() < 0.2, "order {order} (errors {e:?})");
    }
}
