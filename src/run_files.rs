//! A run's output folder as the studies read it back: the final profiles
//! (`profiles.csv`, at the full precision the run wrote) and the summary (`summary.json`),
//! one reading for the sweep's table, the calibration's reference runs, the diagnosis and
//! the warm starts, so that they agree on what a finished run left.

use std::path::Path;

use anyhow::Context;
use saltus_solvers::Profiles;
use serde::de::DeserializeOwned;

use crate::table::Table;

/// The final profiles, the summary and the resolved scene of a run, in its folder (the
/// names the solvers write them under).
pub use saltus_solvers::output::{PROFILES_FILE as PROFILES, SCENE_FILE as SCENE, SUMMARY_FILE as SUMMARY};

/// The columns of `dir/profiles.csv` (an empty cell is NaN).
pub fn profiles_table(dir: &Path) -> anyhow::Result<Table> {
    Table::read_profiles_file(&dir.join(PROFILES))
}

/// The final profiles of the run in `dir`.
pub fn profiles(dir: &Path) -> anyhow::Result<Profiles> {
    let t = profiles_table(dir)?;
    Ok(Profiles { columns: t.names.into_iter().zip(t.columns).collect() })
}

/// The summary of the run in `dir` as `T` (the solvers' `Summary`, or the fields in the
/// order written); `None` when the run wrote none (not run yet).
pub fn summary<T: DeserializeOwned>(dir: &Path) -> anyhow::Result<Option<T>> {
    let f = dir.join(SUMMARY);
    if !f.is_file() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&f).with_context(|| format!("{}: cannot read", f.display()))?;
    serde_json::from_str(&text).map(Some).with_context(|| format!("{}: not a run summary", f.display()))
}
