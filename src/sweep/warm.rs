//! Warm starts: an Eulerian point starts from the steady state of its nearest finished
//! neighbour instead of from rest.

use std::path::Path;

use super::manifest::{Manifest, Status};
use super::spec::Sweep;
use crate::runner;

/// The points of a sweep by their positions on the axes, to find a point's nearest
/// finished neighbour.
#[derive(Debug)]
pub struct Neighbours {
    at: Vec<Vec<usize>>,
}

impl Neighbours {
    /// The positions of `sweep`'s points.
    pub fn new(sweep: &Sweep) -> Self {
        Self { at: sweep.points.iter().map(|p| p.at.clone()).collect() }
    }

    /// Folder of the finished (done) point nearest to point `i` in axis steps (ties to
    /// the lower index), `None` when none is finished.
    pub fn nearest_done(&self, i: usize, m: &Manifest) -> Option<String> {
        let d = |j: usize| self.at[i].iter().zip(&self.at[j]).map(|(a, b)| a.abs_diff(*b)).sum::<usize>();
        (0..self.at.len())
            .filter(|&j| j != i && m.points[j].status == Status::Done)
            .min_by_key(|&j| (d(j), j))
            .map(|j| m.points[j].dir.clone())
    }
}

/// Run `scene` into `dir` from the final state of the run in `from`.
pub fn run_from(
    scene: &saltus_core::scene::Scene,
    dir: &Path,
    from: &Path,
    stop: &mut dyn FnMut(&saltus_solvers::Progress) -> bool,
) -> Result<runner::RunOutcome, saltus_core::Error> {
    let _ = (scene, dir, stop);
    Err(saltus_core::Error::Invalid(format!("{}: warm starts are not available", from.display())))
}
