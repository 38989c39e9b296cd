//! The checks of a scene that need the solver: the solver set up exactly as a run sets
//! it up (configuration, grid, closures, initial state; for the DEM the initial particles,
//! before any deposition step). Both `saltus check` and `saltus run` call [`validate`], so
//! they refuse the same scenes.

use saltus_core::scene::Scene;
use saltus_core::Error;

/// Refuse `scene` if its active solver could not start on it: [`crate::resolve`] without
/// the run. Cheap: no time step is taken (the scene's bounds keep the set-up small).
pub fn validate(scene: &Scene) -> Result<(), Error> {
    crate::resolve(scene).map(|_| ())
}
