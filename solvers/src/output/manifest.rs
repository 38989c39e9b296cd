//! `manifest.json`: what reproduces a run.

use serde::Serialize;

/// `manifest.json`: enough to reproduce the run.
#[derive(Clone, Debug, Serialize)]
pub struct Manifest<'a> {
    /// program version
    pub version: &'static str,
    /// git revision of the build, when built from a checkout
    pub git_revision: &'static str,
    /// scene file as given
    pub scene_file: String,
    /// scene seed
    pub seed: u64,
    /// closure model per family
    pub closures: Vec<(&'static str, &'a str)>,
    /// output files
    pub files: Vec<&'static str>,
    /// wall-clock time of the solve (s)
    pub wall_time_s: f64,
}

/// Git revision baked in at build time, or `unknown`.
pub const GIT_REVISION: &str = match option_env!("SALTUS_GIT_REVISION") {
    Some(r) => r,
    None => "unknown",
};
