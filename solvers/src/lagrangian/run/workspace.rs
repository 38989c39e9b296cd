//! The scratch of a Lagrangian run: refilled by the steps that use it, sized with the
//! state, never part of a checkpoint; and the thread pool the steps run in.

use std::path::Path;

use saltus_core::Error;

use crate::run::timing::Stages;

/// Scratch and pool.
pub struct Workspace {
    /// fluid velocity averaged over each particle at the drag evaluation of the last fluid
    /// update (m/s), ubar_p of the exact exchange
    /// ([`crate::lagrangian::coupling::averaging::CellSums::accumulate`]); with
    /// `drag_velocity = "centre"`, zeros (unused)
    pub(crate) seen: Vec<f64>,
    /// zeros on the column's faces: the shear stress of a run without column, the Re_p of
    /// a hindrance that does not see it
    pub(crate) zero_faces: Vec<f64>,
    /// the modified diagonal of eq 17's implicit diffusion of phi, one per cell
    /// ([`crate::lagrangian::coupling::smoothing::diffuse`])
    pub(crate) diffusion: Vec<f64>,
    /// the pool of `solver.lagrangian.threads`, `None` for the caller's
    pub(crate) pool: Option<rayon::ThreadPool>,
    /// wall time per stage of the step
    pub(crate) stages: Stages,
}

impl Workspace {
    /// Scratch for `n` particles and `cells` fluid cells.
    pub(crate) fn new(n: usize, cells: usize, pool: Option<rayon::ThreadPool>) -> Self {
        Self {
            seen: vec![0.0; n],
            zero_faces: vec![0.0; cells + 1],
            diffusion: vec![0.0; cells],
            pool,
            stages: Stages::new(&super::STAGES),
        }
    }

    /// Scratch sized again for a column of `cells` cells (after the column was fitted to
    /// the deposit, or a state restored).
    pub(crate) fn resize(&mut self, cells: usize) {
        self.zero_faces.clear();
        self.zero_faces.resize(cells + 1, 0.0);
        self.diffusion.resize(cells, 0.0);
    }
}

/// Run `f` in `pool` (the caller's pool when `None`).
pub fn within<R: Send>(pool: Option<&rayon::ThreadPool>, f: impl FnOnce() -> R + Send) -> R {
    match pool {
        Some(p) => p.install(f),
        None => f(),
    }
}

/// A pool of `threads` threads, or `None` for the caller's (rayon's default: all cores).
pub fn pool(threads: usize, file: &Path) -> Result<Option<rayon::ThreadPool>, Error> {
    if threads == 0 {
        return Ok(None);
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map(Some)
        .map_err(|e| Error::Invalid(format!("{}: solver.lagrangian.threads = {threads}: {e}", file.display())))
}
