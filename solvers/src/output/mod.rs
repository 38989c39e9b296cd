//! What a run leaves behind: cell profiles, a summary, the resolved scene and a manifest.
//! One contract for both solvers.

mod files;
mod manifest;
mod profiles;
mod summary;

pub use files::{
    check_out, write_run, CHECKPOINT_FILE, MANIFEST_FILE, PROFILES_FILE, RUN_FILES, SCENE_FILE, SUMMARY_FILE,
    TIMESERIES,
};
pub use manifest::{Manifest, GIT_REVISION};
pub use profiles::{profile_gradient, Profiles};
pub use summary::{finite, Summary, Timing};
