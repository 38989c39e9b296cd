//! The resolved scene that `saltus check` prints (and every run writes as `scene.toml`)
//! is a scene that `check` accepts and resolves to the same text, for random accepted
//! scenes: grains, fluid, gravity, column, cell counts, box, contact law, stiffness,
//! end times and output intervals drawn over and beyond their ranges, both solvers. The
//! draws that `check` refuses are skipped; at least a quarter must be accepted, and a
//! sixteenth of them DEM scenes. The runner is seeded: the same scenes on every run.

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

/// Accepted draws needed out of the cases run.
const CASES: u32 = 96;

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

/// `--set` overrides of a scene of 6 mm grains with a mu(I) closure: the solver, and each
/// other key left alone or (three times in ten) set to a draw.
fn overrides() -> impl Strategy<Value = Vec<String>> {
    let set = |k: &'static str| move |v: f64| format!("{k}={v:e}");
    let choice = |k: &'static str, values: &'static [&'static str]| {
        proptest::sample::select(values).prop_map(move |v| format!("{k}={v}"))
    };
    let parts: Vec<BoxedStrategy<Option<String>>> = vec![
        proptest::option::weighted(0.3, log_uniform(1e-3, 2e-2).prop_map(set("particles.diameter"))).boxed(),
        proptest::option::weighted(0.3, (500.0..5000.0f64).prop_map(set("particles.density"))).boxed(),
        proptest::option::weighted(0.3, choice("fluid.density", &["1000.0", "1.2", "1500.0"])).boxed(),
        proptest::option::weighted(0.3, choice("physics.gravity", &["9.81", "0.0", "1e-300", "1000.0"])).boxed(),
        proptest::option::weighted(0.3, (0.0..0.1f64).prop_map(set("physics.slope"))).boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-4, 0.05).prop_map(set("domain.bed_height"))).boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-3, 1000.0).prop_map(set("domain.water_depth"))).boxed(),
        proptest::option::weighted(0.3, (1usize..150_000).prop_map(|n| format!("domain.cells={n}"))).boxed(),
        choice("solver.type", &["\"eulerian\"", "\"lagrangian\""]).prop_map(Some).boxed(),
        proptest::option::weighted(
            0.3,
            (1.5..15.0f64).prop_map(|f| format!("solver.lagrangian.length={:e}", f * 6e-3)),
        )
        .boxed(),
        proptest::option::weighted(0.3, (1.5..15.0f64).prop_map(|f| format!("solver.lagrangian.width={:e}", f * 6e-3)))
            .boxed(),
        proptest::option::weighted(0.3, choice("solver.lagrangian.fluid", &["\"coupled\"", "\"still\"", "\"off\""]))
            .boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-3, 10.0).prop_map(set("solver.lagrangian.end_time"))).boxed(),
        proptest::option::weighted(0.3, (0.0..0.1f64).prop_map(set("solver.lagrangian.size_dispersion"))).boxed(),
        proptest::option::weighted(0.3, (1usize..1_500_000).prop_map(|n| format!("solver.lagrangian.cells={n}")))
            .boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-8, 1e14).prop_map(set("particles.contact.stiffness"))).boxed(),
        proptest::option::weighted(0.3, choice("particles.contact.law", &["\"linear\"", "\"hertz\""])).boxed(),
        proptest::option::weighted(
            0.3,
            choice("particles.contact.normal_force", &["\"spring_dashpot\"", "\"repulsive\""]),
        )
        .boxed(),
        proptest::option::weighted(0.3, (0.05..1.0f64).prop_map(set("particles.restitution"))).boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-3, 1e3).prop_map(set("solver.eulerian.end_time"))).boxed(),
        proptest::option::weighted(0.3, log_uniform(1e-6, 10.0).prop_map(set("output.timeseries_interval"))).boxed(),
        proptest::option::weighted(
            0.3,
            choice(
                "closures.granular",
                &["{type=\"mu_i\"}", "{type=\"frictional_collisional\"}", "{type=\"mu_i\", phi_max=0.55}"],
            ),
        )
        .boxed(),
    ];
    parts.prop_map(|v| v.into_iter().flatten().collect())
}

const SCENE: &str = "seed = 3\n[particles]\ndiameter = 6e-3\ndensity = 2500.0\n[domain]\nbed_height = 0.02\nwater_depth = 0.05\n[solver.lagrangian]\nlength = 0.03\nwidth = 0.03\nend_time = 0.1\n[closures.granular]\ntype = \"mu_i\"\n";

#[test]
fn check_accepts_the_resolved_scene_it_prints_and_resolves_it_to_the_same_text() {
    saltus_closures::link();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("resolved_scene_roundtrip");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let base = dir.join("scene.toml");
    std::fs::write(&base, SCENE).unwrap();
    let resolved = dir.join("resolved.toml");
    let config = Config { cases: CASES, failure_persistence: None, ..Config::default() };
    let mut runner = TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let accepted = std::cell::Cell::new(0u32);
    let dem = std::cell::Cell::new(0u32);
    let result = runner.run(&overrides(), |set| {
        let Ok(scene) = saltus::runner::load_checked(&base, &set, None) else { return Ok(()) };
        accepted.set(accepted.get() + 1);
        if scene.solver.kind == saltus_core::scene::SolverKind::Lagrangian {
            dem.set(dem.get() + 1);
        }
        let text = scene.to_toml().map_err(|e| TestCaseError::fail(e.to_string()))?;
        std::fs::write(&resolved, &text).unwrap();
        let again = saltus::runner::load_checked(&resolved, &[], None)
            .map_err(|e| TestCaseError::fail(format!("{set:?}: the resolved scene is refused: {e}\n{text}")))?;
        let text_again = again.to_toml().map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(&text_again, &text, "{:?}: resolved to another text", set);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    assert!(accepted.get() >= CASES / 4, "only {} of {CASES} draws accepted", accepted.get());
    assert!(dem.get() >= CASES / 16, "only {} of the accepted draws run the DEM", dem.get());
    eprintln!("{} of {CASES} draws accepted, {} of them DEM scenes", accepted.get(), dem.get());
}
