//! The Lagrangian solver as the driver sees it: one unit of work is one fluid period of
//! DEM steps, first of the deposition ([`Phase::Setup`]), then of the flow
//! ([`Phase::Flow`]), each in the pool of `solver.lagrangian.threads`.

use std::path::Path;
use std::time::Instant;

use saltus_core::Error;

use super::config::FluidMode;
use super::solver::{Lagrangian, Stage};
use crate::output::{self, finite};
use crate::run::{Ending, Phase, Progress, Sample, Stepper};
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
                self.flow_wall = self.flow_wall_before + started.elapsed().as_secs_f64();
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

    /// The transport of the last fluid update (the particle sums it averaged), the largest
    /// fluid shear stress of the column, the level below which 1 % of that transport flows
    /// and the relative change of the steady-state windows. Without fluid there are no
    /// averages: the time, the steps and the granular temperature of the particles.
    fn sample(&self) -> Sample {
        let mut s =
            Sample { time: self.time(), residual: self.steady().change(), steps: self.steps(), ..Sample::default() };
        if self.config().settings.numerics.fluid == FluidMode::Off {
            s.theta_g = finite(self.particles().temperature());
            return s;
        }
        let mat = self.material();
        let scales = output::TransportScales::new(self.scene(), mat.rho_p, mat.d, self.config().domain.water_depth);
        let dz = self.dz();
        let flux = &self.sums.v[0];
        // sum over the slices of V v_x, over the bed area: the transport per unit width
        let qs = flux.iter().sum::<f64>() / (self.cell_volume() / dz);
        s.qs = finite(qs);
        s.qs_star = finite(scales.qs_star(qs));
        if let Some(col) = self.column() {
            let tau = col.shear_stress().iter().fold(0.0f64, |a, t| a.max(t.abs()));
            s.shields = finite(scales.shields(tau));
        }
        let (z1, _) = output::flux_levels_by(flux.len(), |i| i as f64 * dz, |i| flux[i], 0.01, 0.99);
        s.bed_surface = finite(z1);
        s
    }

    fn save(&self, out: &mut Vec<u8>) -> Result<(), String> {
        self.save_state(out)
    }

    fn restore(&mut self, state: &[u8]) -> Result<(), String> {
        self.restore_state(state)
    }

    fn restartable(&self) -> bool {
        true
    }
}
