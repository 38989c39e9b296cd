//! The Lagrangian solver as the driver sees it: one unit of work is one fluid period of
//! DEM steps, first of the deposition ([`Phase::Setup`]), then of the flow
//! ([`Phase::Flow`]), each in the pool of `solver.lagrangian.threads`. It joins the run
//! ([`super::run`]) and its outputs ([`super::output`]).

use super::output::{report, vtk};
use super::run::config::FluidMode;
use super::run::solver::Lagrangian;
use super::run::state::{self, Stage};
use super::run::workspace::within;
use crate::measures::flux_levels::flux_levels_by;
use crate::output::{self, finite};
use crate::run::{Clock, Ending, Limits, Phase, Progress, Sample, Stepper};
use crate::RunReport;

impl Stepper for Lagrangian<'_> {
    fn name(&self) -> &'static str {
        "lagrangian"
    }

    fn limits(&self) -> Limits {
        let n = &self.config().settings.numerics;
        Limits { end_time: n.end_time, end_tolerance: 0.0, max_steps: n.max_steps, wall: None }
    }

    fn step(&mut self, limits: &Limits) -> Option<Ending> {
        // the pool is taken out for the call, so that the work can borrow the solver
        let pool = self.work.pool.take();
        let ending = within(pool.as_ref(), || self.unit_of_work(limits));
        self.work.pool = pool;
        ending
    }

    fn progress(&self) -> Progress {
        let dt = self.dt();
        let total_steps = self.settle_steps() + self.steps();
        match self.state.stage {
            Stage::Deposition => Progress {
                phase: Phase::Setup,
                time: self.settle_steps() as f64 * dt,
                end_time: self.params.settle_total as f64 * dt,
                steps: self.settle_steps(),
                total_steps,
                dt,
                residual: None,
            },
            Stage::Flow => Progress {
                phase: Phase::Flow,
                time: self.time(),
                end_time: self.config().settings.numerics.end_time,
                steps: self.steps(),
                total_steps,
                dt,
                residual: self.steady().change(),
            },
        }
    }

    fn answer(&self) -> Option<crate::run::Answer> {
        self.state.truncation.window().map(|w| crate::run::Answer {
            start: w.start,
            mean: w.mean,
            stderr: w.stderr,
            geweke_z: w.geweke_z,
        })
    }

    fn report(&self, ending: &Ending, clock: &Clock) -> RunReport {
        report::report(self, ending, clock)
    }

    fn stages(&self) -> Vec<(&'static str, f64)> {
        self.dem().stages().iter().chain(self.work.stages.iter()).collect()
    }

    fn worker_cpu(&self) -> Option<f64> {
        // each thread of the run's own pool tells its CPU time; on the caller's pool the
        // threads' time is not the run's alone
        let pool = self.work.pool.as_ref()?;
        pool.broadcast(|_| crate::run::cpu::thread_seconds()).into_iter().sum()
    }

    fn paraview_period(&self) -> f64 {
        self.config().settings.numerics.vtk_period
    }

    /// The particles, and the column the particles see when there is fluid.
    fn paraview(&self) -> Result<Vec<(&'static str, String)>, String> {
        let refuse = |what: &str, array: String| format!("{what} array `{array}` holds a non-finite value");
        let mut docs = vec![("particles", vtk::particles_vtp(self.particles()).map_err(|a| refuse("particle", a))?)];
        if self.config().settings.numerics.fluid != FluidMode::Off {
            docs.push(("column", vtk::column_vtp(&self.state.field).map_err(|a| refuse("column", a))?));
        }
        Ok(docs)
    }

    /// The fields of the last fluid update, not the statistics' time averages that the
    /// report writes: the volume fraction, the column's fluid velocity, the grains' mean
    /// velocity and their flux density (m/s, summing to qs over the cells) per cell.
    fn phase_profiles(&self) -> output::Profiles {
        let n = self.cells();
        let dz = self.dz();
        let mut p = output::Profiles::default();
        p.push("z", (0..n).map(|c| (c as f64 + 0.5) * dz).collect());
        let flux = &self.state.sums.v[0];
        let volume = self.cell_volume();
        let fields: [(&str, &[f64]); 3] =
            [("phi", &self.state.phi), ("u_f", &self.state.field.u), ("u_p", &self.state.u_p)];
        for (name, values) in fields {
            if values.len() == n {
                p.push(name, values.to_vec());
            }
        }
        if flux.len() == n && volume > 0.0 {
            p.push("q_s", flux.iter().map(|f| f / volume).collect());
        }
        p
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
        let scales = self.params.scales;
        let qs = self.state.transport_rate();
        s.qs = finite(qs);
        s.qs_star = finite(scales.qs_star(qs));
        if let Some(col) = self.column() {
            let tau = col.shear_stress().iter().fold(0.0f64, |a, t| a.max(t.abs()));
            s.shields = finite(scales.shields(tau));
        }
        let (dz, flux) = (self.dz(), &self.state.sums.v[0]);
        let (z1, _) = flux_levels_by(flux.len(), |i| i as f64 * dz, |i| flux[i], 0.01, 0.99);
        s.bed_surface = finite(z1);
        s
    }

    fn save(&self, out: &mut Vec<u8>) -> Result<(), String> {
        state::save(&self.state, out)
    }

    fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        let s = state::load(bytes, self.dt(), self.state.column.is_some(), self.state.granular.is_some())?;
        self.adopt(s);
        Ok(())
    }

    fn restartable(&self) -> bool {
        true
    }

    fn warm_start(&mut self, from: &crate::run::WarmStart) -> Result<(), String> {
        match from {
            crate::run::WarmStart::State(r) => {
                let parent = state::decode(&r.state).map_err(|e| format!("{}: {e}", r.file.display()))?;
                let fluid = crate::lagrangian::run::warm::carries_fluid(self.params.scene, r);
                self.warm_start_from(parent, fluid).map_err(|e| format!("{}: {e}", r.file.display()))
            }
            crate::run::WarmStart::Profiles(p) => self.start_from_profiles(p),
        }
    }
}
