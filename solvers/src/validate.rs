//! The checks of a scene that need the solver: its configuration built as a run would
//! build it, and for the Eulerian the column set up (grid, closures, initial state). Both
//! `saltus check` and `saltus run` call [`validate`], so they refuse the same scenes.

use saltus_core::scene::{Scene, SolverKind};
use saltus_core::Error;

use crate::{eulerian, lagrangian};

/// Refuse `scene` if its active solver could not start on it. Cheap: no time step is
/// taken and no particle is created.
pub fn validate(scene: &Scene) -> Result<(), Error> {
    match scene.solver.kind {
        SolverKind::Eulerian => {
            let cfg = eulerian::Config::from_scene(scene)?;
            eulerian::Eulerian::new(scene, cfg).map(|_| ())
        }
        SolverKind::Lagrangian => lagrangian::Config::from_scene(scene).map(|_| ()),
    }
}
