//! Warm starts (`warm_start = true` in the sweep file): a point starts from the final
//! state of its neighbour one step back along the last swept axis (its parent) instead of
//! from rest, once that neighbour has ended done: an Eulerian point from its profiles, a
//! DEM point from the grains of its final checkpoint (every DEM run writes one at its
//! end), with its own fluid column and forcing and without a deposition. Each chain of
//! points along that axis runs in order, the chains in parallel, so that which state a
//! point starts from does not depend on the scheduling: the sweep gives the same numbers
//! on any number of jobs. The first point of a chain, a point whose parent did not end
//! done, and a scene with a two-equation turbulence closure in the Eulerian solver (k and
//! omega are not in the profiles) start from rest; so does a DEM point whose parent's
//! grains its scene cannot take (another count or size of grains, lateral cell, time step
//! or bottom), with the reason in the manifest and the table.

use std::path::Path;

use saltus_core::scene::{Scene, SolverKind};

use super::spec::Sweep;
use crate::runner;

/// The parent of each point of a sweep.
#[derive(Debug)]
pub struct Chains {
    parent: Vec<Option<usize>>,
}

impl Chains {
    /// The parents of `sweep`'s points (none without warm starts).
    pub fn new(sweep: &Sweep) -> Self {
        let axis = sweep.axes.iter().rposition(|a| !a.is_seed() && a.values.len() > 1);
        let parent = sweep
            .points
            .iter()
            .map(|p| {
                let j = axis.filter(|_| sweep.warm_start)?;
                let k = p.at[j].checked_sub(1)?;
                let mut at = p.at.clone();
                at[j] = k;
                sweep.points.iter().position(|q| q.at == at)
            })
            .collect();
        Self { parent }
    }

    /// Point `i`'s parent, if it has one.
    pub fn parent(&self, i: usize) -> Option<usize> {
        self.parent[i]
    }
}

/// Run `scene` into `dir` from the final state of the run in `from`, or from rest when
/// the state cannot start it: then with the reason.
pub fn run_from(
    scene: &Scene,
    dir: &Path,
    from: &Path,
    stop: &mut dyn FnMut(&saltus_solvers::Progress) -> bool,
) -> anyhow::Result<(runner::RunOutcome, Option<String>)> {
    let (warm_start, refused) = match runner::warm_state(scene, from)? {
        Ok(w) => (Some(w), None),
        Err(why) => (None, Some(why)),
    };
    let settings = runner::RunSettings { restart: None, log_every: None, max_wall: None, warm_start };
    Ok((runner::run_scene_with(scene, dir, &indicatif::ProgressBar::hidden(), &settings, stop)?, refused))
}

/// Whether `scene` can start warm: an Eulerian column without transported turbulence, or
/// a DEM run (whose parent's grains are checked when it starts).
pub fn can_start_warm(scene: &Scene) -> bool {
    match scene.solver.kind {
        SolverKind::Eulerian => scene.closures.turbulence.as_ref().is_none_or(|t| t.transported().is_empty()),
        SolverKind::Lagrangian => true,
    }
}
