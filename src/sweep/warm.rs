//! Warm starts (`warm_start = true` in the sweep file): an Eulerian point starts from the
//! final profiles of its neighbour one step back along the last swept axis (its parent)
//! instead of from rest, once that neighbour has finished. Each chain of points along
//! that axis runs in order, the chains in parallel, so that which state a point starts
//! from does not depend on the scheduling: the sweep gives the same numbers on any number
//! of jobs. The first point of a chain, a point whose parent did not end done, and a
//! scene with a two-equation turbulence closure (k and omega are not in the profiles)
//! start from rest.

use std::path::Path;

use anyhow::Context;

use super::spec::Sweep;
use crate::runner;
use crate::table::Table;

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

/// The final profiles a run wrote into `dir`.
pub fn profiles(dir: &Path) -> anyhow::Result<saltus_solvers::Profiles> {
    let t = Table::read_profiles_file(&dir.join("profiles.csv"))
        .with_context(|| format!("{}: no profiles to start from", dir.display()))?;
    Ok(saltus_solvers::Profiles { columns: t.names.into_iter().zip(t.columns).collect() })
}

/// Run `scene` into `dir` from the final state of the run in `from`.
pub fn run_from(
    scene: &saltus_core::scene::Scene,
    dir: &Path,
    from: &Path,
    stop: &mut dyn FnMut(&saltus_solvers::Progress) -> bool,
) -> anyhow::Result<runner::RunOutcome> {
    let settings =
        runner::RunSettings { restart: None, log_every: None, max_wall: None, warm_start: Some(profiles(from)?) };
    Ok(runner::run_scene_with(scene, dir, &indicatif::ProgressBar::hidden(), &settings, stop)?)
}

/// Whether `scene` can start warm: an Eulerian column without transported turbulence.
pub fn can_start_warm(scene: &saltus_core::scene::Scene) -> bool {
    scene.solver.kind == saltus_core::scene::SolverKind::Eulerian
        && scene.closures.turbulence.as_ref().is_none_or(|t| t.transported().is_empty())
}
