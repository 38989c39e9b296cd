//! The files of a run folder: their names, the refusal of a folder where the run would
//! write over one of its inputs, and the writing of the run's outputs.

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_core::Error;

use super::manifest::{Manifest, GIT_REVISION};
use super::profiles::Profiles;
use super::summary::Summary;

fn io(file: PathBuf) -> impl FnOnce(std::io::Error) -> Error {
    move |source| Error::Io { file, source }
}

/// The final profiles of a run, in its folder.
pub const PROFILES_FILE: &str = "profiles.csv";
/// The summary of a run, in its folder; written when the run ends, whatever its ending.
pub const SUMMARY_FILE: &str = "summary.json";
/// The resolved scene of a run, in its folder.
pub const SCENE_FILE: &str = "scene.toml";
/// The manifest of a run (program, closures, files), in its folder.
pub const MANIFEST_FILE: &str = "manifest.json";
/// The time series of a run, in its folder ([`crate::run::history`]).
pub const TIMESERIES: &str = "timeseries.csv";

/// The files [`write_run`] writes, with the time series, in the order of the manifest.
pub const RUN_FILES: [&str; 5] = [PROFILES_FILE, SUMMARY_FILE, SCENE_FILE, MANIFEST_FILE, TIMESERIES];

/// File name of the checkpoint in its folder ([`crate::run::checkpoint`]).
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// Refuse an output folder `dir` that is an empty path, or where a file the run writes
/// ([`RUN_FILES`], the checkpoint) is one of the run's inputs (the scene file, a reference
/// file). The resolved scene may be rewritten over the scene file it was resolved from
/// when the text is the same (a run of a folder's own `scene.toml` into that folder,
/// `--restart` included): nothing is lost then.
pub fn check_out(dir: &Path, scene: &Scene) -> Result<(), Error> {
    let file = scene.path.display();
    if dir.as_os_str().is_empty() {
        return Err(Error::Invalid(format!(
            "{file}: the output folder is an empty path; give a folder (--out or output.dir), or leave output.dir out for out/<meta.name>"
        )));
    }
    let same = |a: &Path, b: &Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y);
    let inputs = std::iter::once(("the scene file", scene.path.clone()))
        .chain(scene.reference.iter().map(|r| ("the reference file", PathBuf::from(&r.file))));
    for (what, input) in inputs {
        for name in RUN_FILES.iter().chain([&CHECKPOINT_FILE]) {
            let written = dir.join(name);
            if !same(&written, &input) {
                continue;
            }
            if *name == SCENE_FILE && what == "the scene file" {
                let unchanged = std::fs::read_to_string(&input).ok() == Some(scene.to_toml()?);
                if unchanged {
                    continue;
                }
            }
            return Err(Error::Invalid(format!(
                "{file}: the run would write {} over {what} {}; choose another output folder (--out or output.dir)",
                written.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

/// Write `profiles.csv`, `summary.json`, `scene.toml` (resolved) and `manifest.json` into
/// `dir` (created if needed).
pub fn write_run(dir: &Path, scene: &Scene, profiles: &Profiles, summary: &Summary) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(io(dir.to_path_buf()))?;
    let put = |name: &str, text: String| -> Result<(), Error> {
        let f = dir.join(name);
        std::fs::write(&f, text).map_err(io(f))
    };
    put(PROFILES_FILE, profiles.to_csv())?;
    let json = serde_json::to_string_pretty(summary).map_err(|e| Error::Invalid(format!("summary: {e}")))?;
    put(SUMMARY_FILE, json + "\n")?;
    put(SCENE_FILE, scene.to_toml()?)?;
    let cl = &scene.closures;
    let name = |m: Option<&dyn saltus_core::Describe>| m.map_or("none", |m| m.name());
    let manifest = Manifest {
        version: env!("CARGO_PKG_VERSION"),
        git_revision: GIT_REVISION,
        scene_file: scene.path.display().to_string(),
        seed: scene.seed,
        closures: vec![
            ("drag", name(cl.drag.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("hindrance", name(cl.hindrance.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("viscosity", name(cl.viscosity.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("granular", name(cl.granular.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("turbulence", name(cl.turbulence.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("fluctuation", name(cl.fluctuation.as_deref().map(|m| m as &dyn saltus_core::Describe))),
            ("wall_friction", name(cl.wall_friction.as_deref().map(|m| m as &dyn saltus_core::Describe))),
        ],
        files: RUN_FILES.to_vec(),
        wall_time_s: summary.wall_time_s,
    };
    let json = serde_json::to_string_pretty(&manifest).map_err(|e| Error::Invalid(format!("manifest: {e}")))?;
    put(MANIFEST_FILE, json + "\n")
}
