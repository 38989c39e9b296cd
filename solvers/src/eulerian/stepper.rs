//! The Eulerian column as a [`Stepper`]: one `step` is one accepted time step, with the
//! adaptive time step and the rejected attempts inside it.
//!
//! The time step grows while phi changes by less than half of `solver.eulerian.max_phi_change`
//! and fields by less than `solver.eulerian.target_field_change` (50 %) per step; an attempt
//! that makes phi negative or reach the maximum packing, or produces a non-finite value, is
//! rejected, the state restored, and retried with 0.3 dt. Below `solver.eulerian.dt_min` the run ends [`Ending::Unstable`] with the
//! last rejection's breakdown. After every accepted step the coefficients are evaluated
//! for the new state, so that the getters and the report read them without advancing
//! anything, and the next step starts from them.

use std::time::Instant;

use saltus_core::scene::TimeStepping;

use super::coefficients::{evaluate, update_local_pressure};
use super::k_omega::solve_two_equation;
use super::momentum::solve_momentum;
use super::rheology::Rheology;
use super::stress::kinetic_pressures;
use super::temperature::solve_temperature;
use super::volume_fraction::solve_phi;
use super::{stage, Eulerian};
use crate::column::bdf2::Bdf2;
use crate::run::{Breakdown, Clock, Ending, Limits, Phase, Progress, Sample, Stepper};
use crate::RunReport;

impl Eulerian<'_> {
    /// One attempt of a step of length `dt` from the current state and coefficients: the
    /// momentum, then the temperature (kinetic) or the pressure at the new shear rate
    /// (local), k and omega, and the volume fraction.
    fn attempt(&mut self, dt: f64) -> Result<Instant, Breakdown> {
        let t = Instant::now();
        self.state.save(&mut self.work.saved);
        let grad = self.pressure_gradient(self.state.time + dt);
        let bdf2 =
            self.accurate().then_some(self.state.stepping.previous.dt).filter(|&p| p > 0.0).map(|p| Bdf2::new(dt / p));
        let t = match bdf2 {
            Some(b) => {
                self.extrapolate(b)?;
                self.work.stages.lap(stage::COEFFICIENTS, t)
            }
            None => t,
        };
        let Self { params, state, work } = self;
        solve_momentum(params, state, work, dt, grad, bdf2)?;
        let t = work.stages.lap(stage::MOMENTUM, t);
        if params.kinetic {
            solve_temperature(params, state, work, dt, bdf2)?;
            if let Rheology::Kinetic { model, .. } = params.m.rheology {
                // the phi step sees the new temperature
                kinetic_pressures(params, state, work, model);
            }
        } else {
            update_local_pressure(params, state, work);
        }
        let t = work.stages.lap(stage::GRANULAR, t);
        solve_two_equation(params, state, work, dt, bdf2)?;
        let t = work.stages.lap(stage::TURBULENCE, t);
        let r = solve_phi(params, state, work, dt, bdf2);
        let t = self.work.stages.lap(stage::VOLUME_FRACTION, t);
        r.map(|()| t)
    }

    /// Put the linear extrapolation of the last two accepted states to the end of a BDF2
    /// step into the state and evaluate the coefficients there, then give k and omega back
    /// their start values (their step extrapolates its own terms): the solves linearise
    /// about this state and take their old values from the saved start and the state
    /// before it, so that no coefficient lags by a step (the semi-implicit BDF2 of
    /// [`crate::column::bdf2`]). phi is kept in [0, the maximum packing) and T >= 0, k >= 0,
    /// omega > 0: a cell whose extrapolation leaves them keeps its start value.
    fn extrapolate(&mut self, b: Bdf2) -> Result<(), Breakdown> {
        let phi_max = self.params.m.rheology.phi_max();
        // the fields one step back, held apart while the state takes the extrapolation
        let p = std::mem::take(&mut self.state.stepping.previous);
        let s = &mut self.state;
        for i in 0..s.phi.len() {
            let v = b.extrapolate(s.phi[i], p.phi[i]);
            if (0.0..phi_max).contains(&v) {
                s.phi[i] = v;
            }
            let v = b.extrapolate(s.temp[i], p.temp[i]);
            if v >= 0.0 {
                s.temp[i] = v;
            }
            s.uf[i] = b.extrapolate(s.uf[i], p.uf[i]);
            s.up[i] = b.extrapolate(s.up[i], p.up[i]);
        }
        for j in 0..s.flux.len() {
            s.flux[j] = b.extrapolate(s.flux[j], p.flux[j]);
            s.drift_flux[j] = b.extrapolate(s.drift_flux[j], p.drift_flux[j]);
        }
        if let Some(kw) = &mut s.kw {
            let col = &mut kw.col;
            for i in 0..p.k.len() {
                let v = b.extrapolate(col.k[i], p.k[i]);
                if v >= 0.0 {
                    col.k[i] = v;
                }
                let v = b.extrapolate(col.omega[i], p.omega[i]);
                if v > 0.0 {
                    col.omega[i] = v;
                }
            }
        }
        self.state.stepping.previous = p;
        let r = evaluate(&self.params, &mut self.state, &mut self.work, false);
        if let Some(kw) = &mut self.state.kw {
            kw.col.restore();
        }
        r
    }

    /// The coefficients of the current state, timed from `since` (the end of the stage
    /// before: one clock read less per step).
    fn coefficients(&mut self, since: Instant) -> Result<(), Breakdown> {
        let r = self.evaluate();
        self.work.stages.lap(stage::COEFFICIENTS, since);
        r
    }

    /// The run's own ending at the current state, if any: the steady state, never in
    /// time-accurate stepping (the driver applies the end time and the step cap).
    fn ending(&self) -> Option<Ending> {
        (!self.accurate() && self.state.stepping.calm >= self.params.cfg.settings.steady_steps)
            .then_some(Ending::Steady)
    }

    /// Whether the momentum is stepped by BDF2 (`solver.eulerian.time_stepping = "accurate"`).
    pub(super) fn accurate(&self) -> bool {
        self.params.cfg.settings.time_stepping == TimeStepping::Accurate
    }

    /// The pressure gradient -dp/dx at time `t` (Pa/m): the steady one and the forcing's.
    pub fn pressure_gradient(&self, t: f64) -> f64 {
        match &self.params.scene.physics.forcing {
            Some(f) => self.params.c.grad + f.gradient(t, self.params.c.rho_f),
            None => self.params.c.grad,
        }
    }

    /// Keep the fields before an accepted step of length `dt` for the next BDF2 step.
    fn remember(&mut self, dt: f64) {
        if !self.accurate() {
            return;
        }
        let p = &mut self.state.stepping.previous;
        let empty: [&[f64]; 2] = [&[], &[]];
        let [k, omega] = self.state.kw.as_ref().map_or(empty, |kw| [kw.col.saved_k(), kw.col.saved_omega()]);
        for (dst, src) in [
            (&mut p.uf, self.work.saved.uf()),
            (&mut p.up, self.work.saved.up()),
            (&mut p.phi, self.work.saved.phi()),
            (&mut p.temp, self.work.saved.temp()),
            (&mut p.k, k),
            (&mut p.omega, omega),
            (&mut p.flux, self.work.saved.flux()),
            (&mut p.drift_flux, self.work.saved.drift_flux()),
        ] {
            dst.clear();
            dst.extend_from_slice(src);
        }
        p.dt = dt;
    }
}

impl Stepper for Eulerian<'_> {
    fn name(&self) -> &'static str {
        "eulerian"
    }

    fn limits(&self) -> Limits {
        let s = &self.params.cfg.settings;
        // the last step is cut to end at end_time, which it meets within rounding
        Limits { end_time: s.end_time, end_tolerance: 1e-12, max_steps: s.max_steps as u64, wall: None }
    }

    fn warm_start(&mut self, from: &crate::run::WarmStart) -> Result<(), String> {
        match from {
            crate::run::WarmStart::Profiles(p) => self.warm_start_from(p),
            crate::run::WarmStart::State(r) => Err(super::warm::checkpoint_refusal(r)),
        }
    }

    fn step(&mut self, limits: &Limits) -> Option<Ending> {
        if let Some(e) = self.ending() {
            return Some(e);
        }
        let s = &self.params.cfg.settings;
        let (dt_max, dt_min, end_time, tol, max_change, field_change) =
            (s.dt_max, s.dt_min, limits.end_time, s.steady_tolerance, s.max_phi_change, s.target_field_change);
        loop {
            let dt = self.state.stepping.dt;
            let step = dt.min(end_time - self.state.time);
            match self.attempt(step) {
                Ok(since) => {
                    self.remember(step);
                    self.state.time += step;
                    self.state.steps += 1;
                    let (rate, grow) = self.state.rates(
                        &self.work.saved,
                        step,
                        self.params.kinetic,
                        max_change,
                        field_change,
                        self.accurate(),
                    );
                    self.state.residual = rate;
                    self.state.stepping.calm = if rate < tol { self.state.stepping.calm + 1 } else { 0 };
                    self.state.stepping.dt = (dt * grow).min(dt_max);
                    if let Err(b) = self.coefficients(since) {
                        return Some(Ending::Unstable(b));
                    }
                    return self.ending();
                }
                Err(b) => {
                    self.state.restore(&self.work.saved);
                    self.state.rejected += 1;
                    self.state.stepping.dt = dt * 0.3;
                    if self.state.stepping.dt < dt_min {
                        // the coefficients of the restored state, for the report
                        let _ = self.coefficients(Instant::now());
                        return Some(Ending::Unstable(b));
                    }
                    if let Err(b) = self.coefficients(Instant::now()) {
                        return Some(Ending::Unstable(b));
                    }
                }
            }
        }
    }

    fn progress(&self) -> Progress {
        Progress {
            phase: Phase::Flow,
            time: self.state.time,
            end_time: self.params.cfg.settings.end_time,
            steps: self.state.steps as u64,
            total_steps: self.state.steps as u64,
            dt: self.state.stepping.dt,
            residual: self.state.residual.is_finite().then_some(self.state.residual),
        }
    }

    fn report(&self, ending: &Ending, clock: &Clock) -> RunReport {
        self.run_report(ending, clock.wall)
    }

    fn stages(&self) -> Vec<(&'static str, f64)> {
        self.work.stages.iter().collect()
    }

    fn sample(&self) -> Sample {
        self.sample_row()
    }
}
