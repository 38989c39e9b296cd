//! A closure table of one solver's face (`[solver.<solver>.closures.<family>]`) replaces
//! the scene's `[closures.<family>]` when that solver runs and only then; the resolved
//! scene records what ran and resolves to the same closures for either solver; a
//! `--set` of the family and a closures file reach the face's table; a face's mistake is
//! refused naming its key, whichever solver is active.

use std::path::{Path, PathBuf};

use saltus_core::param::Describe;
use saltus_core::scene::Scene;

/// Fry's Couette viscosity shared, the clear fluid on the DEM's face.
const SCENE: &str = "seed = 3
[particles]
diameter = 1e-3
density = 2500.0
[domain]
bed_height = 0.01
water_depth = 0.01
[solver.lagrangian]
length = 0.004
width = 0.004
end_time = 0.1
[closures.granular]
type = \"mu_i\"
[closures.viscosity]
type = \"fry2024\"
shields = 0.67
re_p = 1.0
density_ratio = 2.5
[solver.lagrangian.closures.viscosity]
type = \"clear_fluid\"
";

fn scene_file(name: &str, text: &str) -> PathBuf {
    saltus_closures::link();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("solver_faces").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("scene.toml");
    std::fs::write(&f, text).unwrap();
    f
}

fn viscosity(s: &Scene) -> &'static str {
    s.closures.viscosity.as_deref().map(Describe::name).unwrap_or("none")
}

fn load(f: &Path, set: &[&str]) -> Scene {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    saltus::runner::load_checked(f, &set, None).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_face_replaces_the_scene_closure_for_its_solver_only() {
    let f = scene_file("replace", SCENE);
    assert_eq!(viscosity(&load(&f, &[])), "fry2024");
    assert_eq!(viscosity(&load(&f, &["solver.type=lagrangian"])), "clear_fluid");
    assert_eq!(viscosity(&load(&f, &["solver.type=eulerian"])), "fry2024");
}

#[test]
fn the_resolved_scene_records_what_ran_and_resolves_the_same_for_either_solver() {
    let f = scene_file("resolved", SCENE);
    for kind in ["lagrangian", "eulerian"] {
        let text = load(&f, &[&format!("solver.type={kind}")]).to_toml().unwrap();
        let resolved = f.with_file_name(format!("resolved_{kind}.toml"));
        std::fs::write(&resolved, &text).unwrap();
        let table: toml::Table = text.parse().unwrap();
        let ran = table["closures"]["viscosity"]["type"].as_str();
        assert_eq!(ran, Some(if kind == "lagrangian" { "clear_fluid" } else { "fry2024" }), "{text}");
        let again = load(&resolved, &[]);
        assert_eq!(again.to_toml().unwrap(), text, "the resolved scene of the {kind} resolves to another text");
        assert_eq!(viscosity(&load(&resolved, &["solver.type=lagrangian"])), "clear_fluid", "{kind}: {text}");
        assert_eq!(viscosity(&load(&resolved, &["solver.type=eulerian"])), "fry2024", "{kind}: {text}");
    }
}

#[test]
fn a_set_of_the_family_and_a_closures_file_reach_the_face() {
    let f = scene_file("set", SCENE);
    let s = load(&f, &["solver.type=lagrangian", "closures.viscosity={type=\"krieger_dougherty\"}"]);
    assert_eq!(viscosity(&s), "krieger_dougherty");
    let file = f.with_file_name("fitted.toml");
    std::fs::write(&file, "[closures.viscosity]\ntype = \"krieger_dougherty\"\n").unwrap();
    let s = saltus::runner::load_checked(&f, &["solver.type=lagrangian".into()], Some(&file)).unwrap();
    assert_eq!(viscosity(&s), "krieger_dougherty");
    // a key set inside the family is set in the face's table too
    let face =
        SCENE.replace("type = \"clear_fluid\"", "type = \"fry2024\"\nshields = 0.5\nre_p = 1.0\ndensity_ratio = 2.5");
    let f = scene_file("set_key", &face);
    let text = load(&f, &["solver.type=lagrangian", "closures.viscosity.shields=0.8"]).to_toml().unwrap();
    let table: toml::Table = text.parse().unwrap();
    assert_eq!(table["closures"]["viscosity"]["shields"].as_float(), Some(0.8), "{text}");
}

#[test]
fn a_faces_mistake_is_refused_naming_its_key_whichever_solver_runs() {
    let cases: [(&str, &str); 4] = [
        ("[solver.lagrangian.closures.bogus]\ntype = \"x\"\n", "solver.lagrangian.closures.bogus"),
        ("[solver.lagrangian.closures.drag]\ntype = \"no_such_drag\"\n", "solver.lagrangian.closures.drag"),
        ("[solver.lagrangian.closures.drag]\ntype = \"stokes\"\nnot_a_key = 1.0\n", "solver.lagrangian.closures.drag"),
        ("[solver.eulerian.closures]\ndrag = 3\n", "solver.eulerian.closures.drag"),
    ];
    for (i, (extra, key)) in cases.iter().enumerate() {
        let f = scene_file(&format!("refused_{i}"), &format!("{SCENE}{extra}"));
        for kind in ["eulerian", "lagrangian"] {
            let e = saltus::runner::load_checked(&f, &[format!("solver.type={kind}")], None)
                .err()
                .unwrap_or_else(|| panic!("{extra} accepted with the {kind} solver"))
                .to_string();
            assert!(e.contains(key) && e.contains("scene.toml"), "{kind}, {extra}: {e}");
        }
    }
}
