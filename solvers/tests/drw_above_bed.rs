//! The DRW as the peer code applies it (`closures.fluctuation.above_bed`, YADE
//! `HydroForceEngine::turbulentFluctuation` with the bed elevation of Maurin's 2017 script of
//! the Frey runs): the grains inside the bed draw no fluctuation; and its third, spanwise
//! component (`closures.fluctuation.spanwise`).

mod common;

use std::path::Path;

use saltus_core::scene::Scene;
use saltus_solvers::lagrangian::{Config, Lagrangian};
use saltus_solvers::run::{drive, Ending, Quiet};

/// The fluctuations of the mobile grains and their heights after 0.1 s of coupled flow over
/// the small bed of the lagrangian tests (6 d of beads, phi about 0.6), with the DRW.
fn fluctuations_after_a_short_flow(drw: &str) -> (Vec<[f64; 3]>, Vec<f64>, f64) {
    saltus_closures::link();
    let mut set: Vec<String> = common::SMALL_COUPLED_BED.iter().map(|s| s.to_string()).collect();
    set.extend([
        "solver.lagrangian.end_time=0.1".to_string(),
        "solver.lagrangian.stats_start=0.0".to_string(),
        format!("closures.fluctuation={drw}"),
    ]);
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/chassagne2023/case01.toml");
    let scene = Scene::from_file_with(file, &set).expect("scene");
    let cfg = Config::from_scene(&scene).expect("config");
    let mut m = Lagrangian::new(&scene, cfg).expect("solver");
    let ending = drive(&mut m, &mut Quiet).ending;
    assert_eq!(ending, Ending::EndTime);
    let nm = m.mobile();
    let d = m.material().d;
    (m.forces().fluctuations()[..nm].to_vec(), m.particles().z[..nm].to_vec(), d)
}

/// Grains in the lowest 2 d of a 6 d bed sit below any dense peak of phi: with
/// `above_bed` none of them carries a fluctuation, while without it the Reynolds stress the
/// Li-Sawamoto mixing length leaves inside the bed (phi below phi_max) gives them some; the
/// grains at the surface draw in both runs.
#[test]
fn grains_inside_the_bed_draw_no_fluctuation_with_above_bed() {
    let deep = |z: &[f64], d: f64| {
        let low = z.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        let top = z.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        assert!(top - low > 4.0 * d, "a bed of {} d", (top - low) / d);
        move |zp: f64| zp < low + 2.0 * d
    };
    let moving = |f: &[f64; 3]| f.iter().any(|u| *u != 0.0);

    let (fl, z, d) = fluctuations_after_a_short_flow("{type=\"drw\", above_bed=0.5}");
    let is_deep = deep(&z, d);
    let n_deep = z.iter().filter(|&&zp| is_deep(zp)).count();
    assert!(n_deep > 50, "{n_deep} deep grains");
    let deep_moving = fl.iter().zip(&z).filter(|(f, &zp)| is_deep(zp) && moving(f)).count();
    assert_eq!(deep_moving, 0, "{deep_moving} of {n_deep} deep grains carry a fluctuation");
    let drawing = fl.iter().filter(|f| moving(f)).count();
    assert!(drawing > 0, "no grain at all carries a fluctuation");

    let (fl, z, d) = fluctuations_after_a_short_flow("{type=\"drw\"}");
    let is_deep = deep(&z, d);
    let deep_moving = fl.iter().zip(&z).filter(|(f, &zp)| is_deep(zp) && moving(f)).count();
    assert!(deep_moving > 0, "without above_bed no deep grain carries a fluctuation: the test shows nothing");
}

/// With `spanwise` (and a redraw period of 0.01 s, so that every grain has drawn within the
/// 0.1 s) the grains that draw see u'_y of the same variance as u'_z (both sigma^2
/// at each grain, so the ratio of the sums over the N drawing grains is 1 within about
/// sqrt(2 / N) per sum; the bound 0.6-1.6 is over four of those for N > 100); without it no
/// grain sees a spanwise fluctuation.
#[test]
fn spanwise_draws_reach_the_grains_with_the_variance_of_the_normal_ones() {
    let (fl, _, _) = fluctuations_after_a_short_flow("{type=\"drw\", spanwise=true, period=0.01}");
    let drawing: Vec<&[f64; 3]> = fl.iter().filter(|f| f[2] != 0.0).collect();
    assert!(drawing.len() > 100, "{} grains draw", drawing.len());
    let syy: f64 = drawing.iter().map(|f| f[1] * f[1]).sum();
    let szz: f64 = drawing.iter().map(|f| f[2] * f[2]).sum();
    assert!((0.6..1.6).contains(&(syy / szz)), "<u_y^2> / <u_z^2> = {}", syy / szz);
    assert!(drawing.iter().all(|f| f[1] != 0.0));

    let (fl, _, _) = fluctuations_after_a_short_flow("{type=\"drw\", period=0.01}");
    assert!(fl.iter().any(|f| f[2] != 0.0));
    assert!(fl.iter().all(|f| f[1] == 0.0));
}
