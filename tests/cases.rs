//! Every scene under `cases/` loads, resolves and is accepted by its solver's configuration;
//! the Chassagne et al. 2023 table 2 scenes carry the table's parameters (Shields number from
//! the water depth, density ratio, diameter, friction, restitution, bed of 12.5 d).
//!
//! Comparison and calibration files (a top-level `base` key), closure comparison files
//! (`cases/closures/`) and the scene copies inside reference run folders (a folder holding a
//! run's `manifest.json`) are not scenes and are skipped. No solver is run here: the runs belong to the solver
//! tests and to `saltus run`.

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_solvers::eulerian::{Config, Eulerian};

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cases")
}

/// Every `.toml` file under `dir`, recursively, sorted; run folders (a `manifest.json`
/// beside the files, as `saltus run` writes them) hold a copy of the scene they ran, which
/// is an output, not a scene of the case tree.
fn toml_files(dir: &Path, out: &mut Vec<PathBuf>) {
    if dir.join("manifest.json").is_file() {
        return;
    }
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            toml_files(&path, out);
        } else if path.extension().is_some_and(|x| x == "toml") {
            out.push(path);
        }
    }
}

/// Whether the TOML file holds closures files' keys only (`[closures]`, `[fit]`: the
/// `fitted.toml` of `saltus diagnose --fit`), not a scene.
fn is_closures_file(table: &toml::Table) -> bool {
    table.keys().all(|k| saltus_core::scene::CLOSURES_FILE_KEYS.contains(&k.as_str()))
}

/// The scene files: every `.toml` under `cases/` except `cases/closures/`, comparison
/// files (top-level `base` key) and closures files.
fn scene_files() -> Vec<PathBuf> {
    let root = cases_dir();
    let mut all = Vec::new();
    toml_files(&root, &mut all);
    all.sort();
    all.into_iter()
        .filter(|p| !p.starts_with(root.join("closures")))
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let table: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            !table.contains_key("base") && !is_closures_file(&table)
        })
        .collect()
}

/// Every closures file under `cases/` replaces the closures of the dry incline's scene
/// run by the Eulerian solver, as `saltus run --closures` does.
#[test]
fn every_closures_file_loads_over_a_scene() {
    saltus_closures::link();
    let root = cases_dir();
    let mut all = Vec::new();
    toml_files(&root, &mut all);
    let mut n = 0;
    for p in all.iter().filter(|p| !p.starts_with(root.join("closures"))) {
        let table: toml::Table = std::fs::read_to_string(p).unwrap().parse().unwrap();
        if !is_closures_file(&table) {
            continue;
        }
        let scene = root.join("granular/dry_incline.toml");
        let set = ["solver.type=eulerian".to_string(), "domain.bed_phi=0.55".to_string()];
        let s =
            Scene::from_file_with_closures(&scene, &set, Some(p)).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert!(s.meta.closures_file.is_some(), "{}", p.display());
        n += 1;
    }
    assert!(n >= 1, "no closures file under cases/");
}

/// Every compare file under `cases/` (a `base` scene and `[[variant]]` tables) loads, and
/// every variant's scene (the base with the variant's closures file and overrides, as
/// `saltus compare` resolves it) is accepted, without running any.
#[test]
fn every_compare_file_loads_and_its_variants_resolve() {
    saltus_closures::link();
    let root = cases_dir();
    let mut all = Vec::new();
    toml_files(&root, &mut all);
    all.sort();
    let mut files = 0;
    for p in &all {
        let table: toml::Table = std::fs::read_to_string(p).unwrap().parse().unwrap();
        if !(table.contains_key("base") && table.contains_key("variant")) {
            continue;
        }
        let cmp = saltus::compare::load(p, &[]).unwrap_or_else(|e| panic!("{}: {e:#}", p.display()));
        for v in &cmp.variants {
            Scene::from_file_with_closures(&cmp.base, &v.set, v.closures.as_deref())
                .unwrap_or_else(|e| panic!("{}: variant `{}`: {e}", p.display(), v.name));
        }
        files += 1;
    }
    let peer = root.join("maurin2015/precision_dem_peer.toml");
    assert!(all.contains(&peer), "{} missing", peer.display());
    assert!(files >= 5, "{files} compare files under cases/");
}

fn solver_type(scene: &Scene) -> Option<String> {
    Some(scene.solver.kind.name().to_string())
}

fn load(path: &Path) -> Scene {
    saltus_closures::link();
    Scene::from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Check a reference data file the way `[reference]` describes it: rows of numbers separated
/// by whitespace or commas, `#` lines and blank lines skipped, as many values per row as
/// `columns` names.
fn check_reference_file(scene: &Path, file: &Path, columns: &[String]) -> usize {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {}: {e}", scene.display(), file.display()));
    let mut rows = 0;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split(|c: char| c.is_whitespace() || c == ',').filter(|c| !c.is_empty()).collect();
        assert_eq!(
            cells.len(),
            columns.len(),
            "{}: {}:{}: {} values for columns {:?}",
            scene.display(),
            file.display(),
            i + 1,
            cells.len(),
            columns
        );
        for (cell, name) in cells.iter().zip(columns) {
            assert!(
                cell.parse::<f64>().is_ok_and(f64::is_finite),
                "{}: {}:{}: column `{name}`: `{cell}` is not a finite number",
                scene.display(),
                file.display(),
                i + 1
            );
        }
        rows += 1;
    }
    assert!(rows > 0, "{}: {} has no data rows", scene.display(), file.display());
    rows
}

#[test]
fn the_case_tree_holds_the_expected_scenes() {
    let files = scene_files();
    let root = cases_dir();
    let names: Vec<String> =
        files.iter().map(|p| p.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/")).collect();
    for id in 1..=19 {
        let name = format!("chassagne2023/case{id:02}.toml");
        assert!(names.contains(&name), "missing {name}");
    }
    for name in [
        "revil_baudard2015/sheet_flow_mu_i.toml",
        "fry2024/couette_bedload.toml",
        "verification/couette_laminar.toml",
        "verification/open_channel_laminar.toml",
        "verification/hindered_settling.toml",
        "verification/dry_mu_i_incline.toml",
        "verification/log_layer_mixing_length.toml",
        "maurin2015/frey_sim6.toml",
        "maurin2015/frey_sim14.toml",
        "maurin2015/frey_sim20.toml",
        "maurin2015/sweep3d.toml",
        "verification/dem_binary_collision.toml",
        "verification/dem_sliding_sphere.toml",
        "verification/dem_settling.toml",
        "verification/dem_homogeneous_cooling.toml",
        "maurin2015/peer_bedload_1165.toml",
    ] {
        assert!(names.contains(&name.to_string()), "missing {name}");
    }
}

#[test]
fn every_scene_loads_and_its_solver_accepts_it() {
    let files = scene_files();
    assert!(!files.is_empty(), "no scene under {}", cases_dir().display());
    for path in &files {
        let scene = load(path);
        assert!(!scene.meta.name.is_empty(), "{}: meta.name is empty", path.display());
        let text = std::fs::read_to_string(path).unwrap();
        assert!(text.starts_with('#'), "{}: no header comment giving the source", path.display());
        match solver_type(&scene).as_deref() {
            Some("eulerian") => {
                let cfg = Config::from_scene(&scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                // building the column checks what only the solver knows (bed_phi against the
                // closure's packing, the closures it needs); it runs no step
                if let Err(e) = Eulerian::new(&scene, cfg) {
                    panic!("{}: {e}", path.display());
                }
            }
            Some("lagrangian") => {
                use saltus_solvers::lagrangian;
                let cfg = lagrangian::Config::from_scene(&scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                // places the initial particles and builds the column; runs no step
                if let Err(e) = lagrangian::Lagrangian::new(&scene, cfg) {
                    panic!("{}: {e}", path.display());
                }
            }
            other => eprintln!("{}: solver.type {other:?}: loaded, not checked further", path.display()),
        }
    }
}

#[test]
fn reference_data_files_have_the_named_numeric_columns() {
    for path in scene_files() {
        let scene = load(&path);
        for r in &scene.reference {
            assert_eq!(
                r.columns.first().map(String::as_str),
                Some("z"),
                "{}: first reference column must be z",
                path.display()
            );
            let file = path.parent().unwrap().join(&r.file);
            // the shared data folder lives outside the repository; a checkout without it cannot
            // check the file, only the scene
            if !file.exists() {
                saltus_core::data::missing(&file, &format!("the reference file of {}", path.display()));
                continue;
            }
            check_reference_file(&path, &file, &r.columns);
        }
    }
}

/// Chassagne, Bonamy & Chauchat 2023, table 2: id, theta, r = rho_p/rho_f, d (mm), mu_p, e.
const TABLE2: [(u32, f64, f64, f64, f64, f64); 19] = [
    (1, 0.6, 2.5, 6.0, 0.4, 0.7),
    (2, 0.2, 2.5, 6.0, 0.4, 0.7),
    (3, 0.4, 2.5, 6.0, 0.4, 0.7),
    (4, 0.8, 2.5, 6.0, 0.4, 0.7),
    (5, 1.0, 2.5, 6.0, 0.4, 0.7),
    (6, 0.6, 1.75, 6.0, 0.4, 0.7),
    (7, 0.6, 3.25, 6.0, 0.4, 0.7),
    (8, 0.6, 4.0, 6.0, 0.4, 0.7),
    (9, 0.6, 2.5, 6.0, 0.0, 0.7),
    (10, 0.6, 2.5, 6.0, 0.1, 0.7),
    (11, 0.6, 2.5, 6.0, 0.2, 0.7),
    (12, 0.6, 2.5, 6.0, 0.6, 0.7),
    (13, 0.6, 2.5, 6.0, 0.8, 0.7),
    (14, 0.6, 2.5, 6.0, 1.5, 0.7),
    (15, 0.6, 2.5, 6.0, 0.4, 0.3),
    (16, 0.6, 2.5, 6.0, 0.4, 0.5),
    (17, 0.6, 2.5, 6.0, 0.4, 0.9),
    (18, 0.6, 2.5, 3.0, 0.4, 0.7),
    (19, 0.6, 2.5, 9.0, 0.4, 0.7),
];

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn chassagne2023_scenes_match_table_2() {
    for (id, theta, r, d_mm, mu_p, e) in TABLE2 {
        let path = cases_dir().join(format!("chassagne2023/case{id:02}.toml"));
        let scene = load(&path);
        if let Err(err) = Config::from_scene(&scene) {
            panic!("{}: {err}", path.display());
        }
        let where_ = path.display();
        let rho_f = scene.fluid.density;
        let rho_p = scene.particles.density;
        let d = scene.particles.diameter;
        let slope = scene.physics.slope;
        let h_w = scene.domain.water_depth;

        // the paper's definition (section 3.1): theta = rho_f h_w sin(alpha) / ((rho_p - rho_f) d)
        let theta_scene = rho_f * h_w * slope / ((rho_p - rho_f) * d);
        assert!((theta_scene - theta).abs() <= 1e-9, "{where_}: theta = {theta_scene}, table 2 says {theta}");

        assert!(close(rho_p / rho_f, r, 1e-12), "{where_}: rho_p/rho_f = {}, table 2 says {r}", rho_p / rho_f);
        assert!(close(rho_f, 1000.0, 1e-12), "{where_}: rho_f = {rho_f}");
        assert!(close(scene.fluid.viscosity, 1e-6, 1e-12), "{where_}: nu_f = {}", scene.fluid.viscosity);
        assert!(close(d, d_mm * 1e-3, 1e-12), "{where_}: d = {d}, table 2 says {d_mm} mm");
        assert!(close(slope, 0.05, 1e-12), "{where_}: slope = {slope}");
        assert!(close(scene.domain.bed_height, 12.5 * d, 1e-12), "{where_}: bed_height = {}", scene.domain.bed_height);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{where_}: {e}"));
        let raw: toml::Table = text.parse().unwrap_or_else(|e| panic!("{where_}: {e}"));
        assert!(raw["domain"].get("bed_phi").is_none(), "{where_}: bed_phi must be the default");

        let granular = scene.closures.granular.as_deref().expect("granular closure");
        assert_eq!(granular.name(), "frictional_collisional", "{where_}");
        let param = |name: &str| {
            granular
                .params()
                .into_iter()
                .find(|p| p.name == name)
                .unwrap_or_else(|| panic!("{where_}: no granular parameter {name}"))
                .value
        };
        assert!(close(param("friction"), mu_p, 1e-12), "{where_}: mu_p = {}, table 2 says {mu_p}", param("friction"));
        assert!(close(param("restitution"), e, 1e-12), "{where_}: e = {}, table 2 says {e}", param("restitution"));
        // the grains' own values, which the DEM uses too
        assert!(close(scene.particles.friction, mu_p, 1e-12), "{where_}: particles.friction");
        assert!(close(scene.particles.restitution, e, 1e-12), "{where_}: particles.restitution");

        // only case 1 has reference data (the DEM profile in shared/data)
        assert_eq!(!scene.reference.is_empty(), id == 1, "{where_}: [reference] only for case 1");
    }
}

#[test]
fn the_peer_bedload_scene_has_the_numbers_of_the_peer_script() {
    // the peer's example script derives its numbers from a few inputs (d = 6 mm, rho_p =
    // 2500, phi_max = 0.61, 10 layers, a 10 d x 10 d cell, a channel angle of 0.05 rad,
    // 17.5 d of water); the scene must give the same
    let path = cases_dir().join("maurin2015/peer_bedload_1165.toml");
    let scene = load(&path);
    let l = &scene.solver.lagrangian;
    let (d, rho_p, rho_f, g) = (6e-3, 2500.0, 1000.0, 9.81);
    let (phi_max, layers, angle) = (0.61, 10.0, 0.05f64);
    assert!(close(scene.particles.diameter, d, 1e-12) && close(scene.particles.density, rho_p, 1e-12));
    assert!(close(scene.fluid.density, rho_f, 1e-12) && close(scene.physics.gravity, g, 1e-12));
    assert!((scene.physics.slope - angle.sin()).abs() < 1e-15, "slope {}", scene.physics.slope);
    // int(N_layer phi_max L W / (pi d^3 / 6)) mobile spheres
    let count = (layers * phi_max * 10.0 * 10.0 / saltus_core::grain::sphere_volume(1.0)) as usize;
    assert_eq!(l.particles, Some(count));
    assert_eq!(count, 1165);
    assert!(close(l.length.unwrap_or(0.0), 10.0 * d, 1e-12) && close(l.width.unwrap_or(0.0), 10.0 * d, 1e-12));
    assert!(close(scene.domain.bed_height, layers * d, 1e-12) && close(scene.domain.water_depth, 17.5 * d, 1e-12));
    // k_n = (rho_p - rho_f) phi_max N_layer d g cos(angle) d 1e4, printed to 4 digits
    let kn = (rho_p - rho_f) * phi_max * layers * d * g * angle.cos() * d * 1e4;
    let stiffness = scene.particles.contact.stiffness.unwrap_or(0.0);
    assert!((stiffness / kn - 1.0).abs() < 2e-4, "k_n {stiffness} against {kn}");
    assert!(close(scene.particles.contact.tangential_ratio, 0.5, 1e-12));
    assert!(close(scene.particles.restitution, 0.7, 1e-12) && close(scene.particles.friction, 0.5, 1e-12));
    assert!(close(l.fluid_period, 1e-2, 1e-12) && close(l.end_time, 15.0, 1e-12) && close(l.stats_start, 7.0, 1e-12));
    // fluid cells of d/30 over the bed and the water
    assert_eq!(l.cells, Some(((layers + 17.5) * 30.0) as usize));
}

/// The files a row of `docs/cases.md`'s tables names in its first cell: backticked paths
/// relative to `cases/`, separated by `,` or `...` (a range of files of one folder, in
/// name order); a name without a folder is in the folder of the name before it, and a name
/// ending in `/` covers its folder.
struct Listed {
    files: Vec<String>,
    ranges: Vec<(String, String)>,
    folders: Vec<String>,
}

fn listed_in_cases_md() -> Listed {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/cases.md")).expect("docs/cases.md");
    let mut listed = Listed { files: Vec::new(), ranges: Vec::new(), folders: Vec::new() };
    for line in text.lines().filter(|l| l.starts_with("| `")) {
        let cell = line.split('|').nth(1).unwrap_or("");
        let mut folder = String::new();
        let mut previous: Option<String> = None;
        let mut in_range = false;
        for (i, part) in cell.split('`').enumerate() {
            if i % 2 == 0 {
                in_range |= part.contains("...");
                continue;
            }
            if part.ends_with('/') {
                listed.folders.push(part.to_string());
                continue;
            }
            let full = if part.contains('/') {
                folder = part.rsplit_once('/').map(|(f, _)| format!("{f}/")).unwrap_or_default();
                part.to_string()
            } else {
                format!("{folder}{part}")
            };
            if in_range {
                if let Some(start) = previous.take() {
                    listed.ranges.push((start, full.clone()));
                }
                in_range = false;
            }
            listed.files.push(full.clone());
            previous = Some(full);
        }
    }
    listed
}

#[test]
fn every_file_under_cases_is_listed_in_the_cases_page() {
    let root = cases_dir();
    let mut all = Vec::new();
    toml_files(&root, &mut all);
    let listed = listed_in_cases_md();
    let mut missing = Vec::new();
    for path in &all {
        let rel = path.strip_prefix(&root).expect("under cases/").to_string_lossy().replace('\\', "/");
        let named = listed.files.contains(&rel)
            || listed.folders.iter().any(|f| rel.starts_with(f.as_str()))
            || listed.ranges.iter().any(|(a, b)| {
                let folder = |s: &str| s.rsplit_once('/').map(|(f, _)| f.to_string());
                folder(a) == folder(&rel) && a.as_str() <= rel.as_str() && rel.as_str() <= b.as_str()
            });
        if !named {
            missing.push(rel);
        }
    }
    assert!(missing.is_empty(), "docs/cases.md does not list: {missing:?}");
}
