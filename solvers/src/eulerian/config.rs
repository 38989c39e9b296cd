//! The Eulerian view of a scene: `[domain]` and `[solver.eulerian]`, typed and checked
//! at load by [`saltus_core::scene`]; here only resolved into the numbers the solver uses.

use saltus_core::scene::Scene;
use saltus_core::Error;

pub use saltus_core::scene::{Domain, EulerianSettings as Settings, Top};

/// Checked configuration of one Eulerian run (the column itself is the scene's
/// `[domain]`, read there).
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// number of cells: `domain.cells`, resolved (the default d/4 grid when absent)
    pub cells: usize,
    /// the numerics
    pub settings: Settings,
}

impl Config {
    /// The Eulerian configuration of `scene`, whatever its active solver. The scene was
    /// checked when loaded; a cell count it could not default is refused here.
    pub fn from_scene(scene: &Scene) -> Result<Config, Error> {
        let cells = scene.domain.cells.ok_or_else(|| Error::Key {
            file: scene.path.clone(),
            key: "domain.cells".into(),
            message: "missing, and the default d/4 grid is too fine; give it".into(),
        })?;
        Ok(Config { cells, settings: scene.solver.eulerian.clone() })
    }
}
