//! The Lagrangian solver as the driver sees it: one unit of work is one fluid period of
//! DEM steps, first of the deposition ([`Phase::Setup`]), then of the flow
//! ([`Phase::Flow`]), each in the pool of `solver.lagrangian.threads`.

use std::path::Path;
use std::time::Instant;

use saltus_core::Error;

use super::solver::{Lagrangian, Stage};
use crate::run::{Ending, Phase, Progress, Stepper};
use crate::RunReport;

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

impl Lagrangian<'_> {
    /// Run the deposition to its end (nothing to do without one). `Err` with the ending
    /// when the run ended during it (step cap, breakdown).
    pub fn deposit(&mut self) -> Result<(), Ending> {
        while self.stage == Stage::Deposition {
            if let Some(e) = self.step() {
                return Err(e);
            }
        }
        Ok(())
    }

    /// One fluid period of the current phase, timing the flow for the throughput.
    fn unit_of_work(&mut self) -> Option<Ending> {
        match self.stage {
            Stage::Deposition => self.deposit_period(),
            Stage::Flow => {
                let started = *self.flow_started.get_or_insert_with(Instant::now);
                let ending = self.advance();
                self.flow_wall = started.elapsed().as_secs_f64();
                ending
            }
        }
    }
}

impl Stepper for Lagrangian<'_> {
    fn name(&self) -> &'static str {
        "lagrangian"
    }

    fn step(&mut self) -> Option<Ending> {
        // the pool is taken out for the call, so that the work can borrow the solver
        let pool = self.pool.take();
        let ending = within(pool.as_ref(), || self.unit_of_work());
        self.pool = pool;
        ending
    }

    fn progress(&self) -> Progress {
        let dt = self.dt();
        match self.stage {
            Stage::Deposition => Progress {
                phase: Phase::Setup,
                time: self.settle_steps as f64 * dt,
                end_time: self.settle_total as f64 * dt,
                steps: self.settle_steps,
                dt,
                residual: None,
            },
            Stage::Flow => Progress {
                phase: Phase::Flow,
                time: self.time(),
                end_time: self.config().settings.numerics.end_time,
                steps: self.steps(),
                dt,
                residual: self.steady().change(),
            },
        }
    }

    fn report(&self, ending: &Ending, wall: f64) -> RunReport {
        super::report::report(self, ending, wall)
    }

    fn set_output_dir(&mut self, dir: &Path) {
        self.set_vtk_dir(&dir.join("vtk"));
    }
}
