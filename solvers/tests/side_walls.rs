//! The side-wall friction of the fluid column (Maurin et al. 2015 section III B,
//! `solvers/src/column/side_walls.rs`, with the `graf_altinakar` closure of the
//! `wall_friction` family, whose own law is tested beside it): the laminar slot against
//! its closed form, the momentum balance of a turbulent column, and the limit of wide
//! channels. Run with `cargo test --release -p saltus-solvers --test side_walls`.

use std::path::Path;

use saltus_closures::wall_friction::graf_altinakar::RE_LAMINAR;
use saltus_closures::wall_friction::GrafAltinakar;
use saltus_core::closure::Family;
use saltus_core::scene::{closure_from_value, parse_table};
use saltus_core::{EffectiveViscosity, Turbulence, WallFriction};
use saltus_solvers::column::{Closures, ColumnError, ColumnParams, Coupling, FluidColumn, Grid, SideWalls};

fn turbulence(text: &str) -> Box<dyn Turbulence> {
    saltus_closures::link();
    let t = parse_table(text, Path::new("test")).expect("toml");
    closure_from_value(t.into(), Family::Turbulence, Path::new("test"), "closures.turbulence").expect("turbulence")
}

fn clear_fluid() -> Box<dyn EffectiveViscosity> {
    saltus_closures::link();
    let t = parse_table("type = \"clear_fluid\"", Path::new("test")).expect("toml");
    closure_from_value(t.into(), Family::Viscosity, Path::new("test"), "closures.viscosity").expect("viscosity")
}

/// A laminar slot of width W between the walls: gamma_w = 12 mu / W^2 and the column is
/// the Brinkman equation nu u'' - 12 nu u / W^2 + g_x = 0, u(0) = 0, u'(H) = 0, whose
/// solution is u = U (1 - cosh(k (H - z)) / cosh(k H)), U = g_x W^2 / (12 nu),
/// k = sqrt(12) / W (the plane-Poiseuille mean velocity far from the bottom).
#[test]
fn laminar_slot_matches_the_brinkman_profile() {
    let lam = turbulence("type = \"laminar\"");
    let clear = clear_fluid();
    let walls = GrafAltinakar::default();
    let closures = Closures { viscosity: clear.as_ref(), turbulence: lam.as_ref(), wall_friction: Some(&walls) };
    let (w, h, nu, gx) = (1.0e-3, 2.0e-3, 1.0e-6, 1.2);
    let u_slot = gx * w * w / (12.0 * nu);
    assert!(u_slot * w / nu < RE_LAMINAR);
    let k = 12f64.sqrt() / w;
    for n in [100, 200] {
        let params =
            ColumnParams { gravity_x: gx, side_walls: Some(SideWalls { width: w }), ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
        let zero = vec![0.0; n];
        let c = Coupling { phi: &zero, beta: &zero, u_p: &zero };
        col.solve_steady(&c, &closures, 1e-12, 20).unwrap();
        let err = col
            .velocity()
            .iter()
            .zip(col.grid().centres())
            .map(|(u, &z)| (u - u_slot * (1.0 - (k * (h - z)).cosh() / (k * h).cosh())).abs() / u_slot)
            .fold(0.0, f64::max);
        println!("laminar slot, {n} cells: largest error {err:.2e} of U = {u_slot} m/s");
        assert!(err < 2e-4, "{n} cells: {err}");
        // the bottom carries the rest of the driving: rho g_x H = tau_bed + walls
        let drive = 1000.0 * gx * h;
        let balance = (col.wall_shear_stress() + col.side_wall_stress() - drive).abs() / drive;
        assert!(balance < 1e-10, "balance {balance}");
        let tau_bed = 1000.0 * nu * u_slot * k * (k * h).tanh();
        assert!((col.wall_shear_stress() / tau_bed - 1.0).abs() < 2e-3, "tau_bed {}", col.wall_shear_stress());
    }
}

/// A turbulent channel (mixing length): at steady state the driving over the column
/// equals the bed shear plus the friction of the walls, the latter summed here from the
/// velocity profile and the friction law (not from the column's coefficients), within the
/// steady tolerance; and the walls take a fraction of the driving that grows as the
/// channel narrows.
#[test]
fn turbulent_column_balances_driving_against_bed_and_walls() {
    let ml = turbulence("type = \"mixing_length\"\nform = \"prandtl\"");
    let clear = clear_fluid();
    let walls = GrafAltinakar::default();
    let closures = Closures { viscosity: clear.as_ref(), turbulence: ml.as_ref(), wall_friction: Some(&walls) };
    let (h, n, gx, nu, rho) = (0.02, 200, 0.98, 1.0e-6, 1000.0);
    let zero = vec![0.0; n];
    let c = Coupling { phi: &zero, beta: &zero, u_p: &zero };
    let mut last_share = 0.0;
    for w in [0.1, 0.02, 6.5e-3] {
        let params =
            ColumnParams { gravity_x: gx, side_walls: Some(SideWalls { width: w }), ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::uniform(n, h).unwrap(), params).unwrap();
        col.solve_steady(&c, &closures, 1e-10, 2000).unwrap();
        let walls: f64 = col
            .velocity()
            .iter()
            .zip(col.grid().dz())
            .map(|(&u, &dz)| 2.0 / w * rho * walls.friction_factor(u.abs() * w / nu) * u * u / 8.0 * dz)
            .sum();
        let drive = rho * gx * h;
        let imbalance = (drive - col.wall_shear_stress() - walls).abs() / drive;
        let share = walls / drive;
        println!(
            "W = {w} m: bed {:.4} Pa, walls {walls:.4} Pa ({:.1} % of the driving), imbalance {imbalance:.1e}, surface u {:.3} m/s",
            col.wall_shear_stress(),
            100.0 * share,
            col.velocity()[n - 1]
        );
        assert!(imbalance < 1e-6, "W = {w}: {imbalance}");
        assert!(share > last_share, "W = {w}: share {share} after {last_share}");
        last_share = share;
    }
}

/// W -> infinity: the column without walls, to round-off.
#[test]
fn wide_channel_recovers_the_column_without_walls() {
    let ml = turbulence("type = \"mixing_length\"\nform = \"prandtl\"");
    let clear = clear_fluid();
    let walls = GrafAltinakar::default();
    let closures = Closures { viscosity: clear.as_ref(), turbulence: ml.as_ref(), wall_friction: Some(&walls) };
    let n = 120;
    let zero = vec![0.0; n];
    let phi: Vec<f64> = (0..n).map(|i| if i < 30 { 0.5 } else { 0.0 }).collect();
    let beta: Vec<f64> = (0..n).map(|i| if i < 30 { 1e5 } else { 0.0 }).collect();
    let c = Coupling { phi: &phi, beta: &beta, u_p: &zero };
    let run = |walls: Option<SideWalls>| {
        let params = ColumnParams { gravity_x: 0.5, diameter: 6e-3, side_walls: walls, ..ColumnParams::default() };
        let mut col = FluidColumn::new(Grid::uniform(n, 0.03).unwrap(), params).unwrap();
        for _ in 0..200 {
            col.step(1e-2, &c, &closures).unwrap();
        }
        col.velocity().to_vec()
    };
    let bare = run(None);
    let wide = run(Some(SideWalls { width: 1e12 }));
    let worst = bare.iter().zip(&wide).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let top = bare[n - 1];
    println!("W = 1e12 m against no walls: largest difference {worst:.1e} m/s of {top:.3} m/s");
    assert!(worst <= 1e-12 * top, "{worst}");
    let narrow = run(Some(SideWalls { width: 6.5e-3 }));
    assert!(narrow[n - 1] < 0.9 * top, "narrow channel {} against {top}", narrow[n - 1]);
}

#[test]
fn bad_width_is_refused() {
    for w in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let params = ColumnParams { side_walls: Some(SideWalls { width: w }), ..ColumnParams::default() };
        let err = FluidColumn::new(Grid::uniform(10, 0.01).unwrap(), params).unwrap_err();
        assert!(matches!(err, ColumnError::InvalidParameter { name: "side-wall width", .. }), "{w}: {err}");
    }
}

/// The scene's `[closures.wall_friction]`: refused at load (so by `check` and `run` alike)
/// without the walls, without a fluid column or in the Eulerian solver, naming the file and
/// the key; an unknown model names the known ones; on in the Frey scenes.
#[test]
fn scene_table_needs_walls_and_a_coupled_fluid() {
    use saltus_core::scene::Scene;
    saltus_closures::link();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/maurin2015/frey_sim6.toml");
    let load = |sets: &[&str]| {
        Scene::from_file_with(&file, &sets.iter().map(|s| s.to_string()).collect::<Vec<_>>()).map_err(|e| e.to_string())
    };
    let scene = load(&[]).expect("frey_sim6");
    assert_eq!(scene.closures.wall_friction.as_deref().map(|m| m.name()), Some("graf_altinakar"));
    let off = load(&["closures.wall_friction={type=\"none\"}"]).expect("none");
    assert_eq!(off.closures.wall_friction.as_deref().map(|m| m.poiseuille_number(1e4)), Some(0.0));
    for (sets, allowed) in [
        (&["solver.lagrangian.side_walls=false", "solver.lagrangian.width=0.12"][..], "side_walls = true"),
        (&["solver.lagrangian.fluid=\"still\""][..], "fluid = \"coupled\""),
        (&["solver.type=\"eulerian\"", "domain.cells=200"][..], "no channel width"),
        (&["closures.wall_friction.type=\"smooth\""][..], "graf_altinakar"),
    ] {
        let err = load(sets).expect_err("refused");
        assert!(
            err.contains("frey_sim6.toml") && err.contains("closures.wall_friction") && err.contains(allowed),
            "{sets:?}: {err}"
        );
    }
}
