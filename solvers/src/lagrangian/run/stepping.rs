//! The stepping of the flow: one DEM step with the fluid force of the current field, the
//! fluid update every fluid period (averages, column solve, field refresh, statistics),
//! the checks of the state, and the unit of work the driver calls. Every stage's wall
//! time is counted ([`super::STAGES`]).

use std::borrow::Cow;
use std::time::Instant;

use saltus_core::scene::{ContactModel, DragVelocity};

use super::config::FluidMode;
use super::params::Params;
use super::sampling::{average, dry_sample, sample_due, sample_granular};
use super::solver::{Lagrangian, CHECK_STEPS, MAX_OVERLAP, MAX_SPEED};
use super::stage;
use super::state::{Stage, State};
use super::workspace::Workspace;
use crate::column::Closures;
use crate::lagrangian::coupling::exchange::{step_column, ExchangeModels, Grains};
use crate::run::{Breakdown, Ending, Limits, Place, Stepper};

/// One DEM step with the fluid force of the current fluid field; with `sampled`, the
/// step takes the contact sums of the granular fields.
pub(crate) fn dem_step(params: &Params, state: &mut State, work: &mut Workspace, all: bool, sampled: bool) {
    if params.cfg.settings.numerics.fluid != FluidMode::Off {
        let t0 = Instant::now();
        let upto = if all { state.dem.p.len() } else { state.dem.p.n_mobile };
        let models = params.models();
        let dt = state.dem.dt();
        let State { dem, forces, field, .. } = state;
        let (p, ext) = dem.particles_and_external_force();
        forces.evaluate(p, field, &models, dt, upto, ext);
        if all && models.velocity == DragVelocity::SphereAverage {
            // the exact exchange needs the fluid velocity each grain's drag saw,
            // before the step moves it
            let p = &state.dem.p;
            work.seen.resize(p.len(), 0.0);
            for ((s, &z), &r) in work.seen.iter_mut().zip(&p.z).zip(&p.radius) {
                *s = state.field.sphere_velocity(z, r);
            }
        }
        work.stages.lap(stage::DRAG, t0);
    }
    let slices = sampled.then(|| state.slices());
    state.dem.step_sampled(slices);
}

/// First non-finite or runaway particle, then grains that pass through each other
/// (an overlap beyond [`MAX_OVERLAP`] of a diameter).
pub(crate) fn check(params: &Params, state: &State) -> Result<(), Breakdown> {
    let time = state.phase_time();
    if let Some((a, field, value)) = state.dem.first_non_finite() {
        return Err(Breakdown {
            time,
            place: Place::Particle { index: a },
            field: Cow::Borrowed(field),
            value,
            reason: "not finite".into(),
        });
    }
    let p = &state.dem.p;
    for a in 0..p.n_mobile {
        let s2 = p.vx[a] * p.vx[a] + p.vy[a] * p.vy[a] + p.vz[a] * p.vz[a];
        if s2 > MAX_SPEED * MAX_SPEED {
            return Err(Breakdown {
                time,
                place: Place::Particle { index: a },
                field: Cow::Borrowed("|v|"),
                value: s2.sqrt(),
                reason: speed_cause(params, state, p.z[a]),
            });
        }
    }
    if let Some((a, overlap)) = state.dem.deepest_overlap().filter(|&(_, o)| o > MAX_OVERLAP) {
        return Err(Breakdown {
            time,
            place: Place::Particle { index: a },
            field: Cow::Borrowed("overlap / d"),
            value: overlap,
            reason: overlap_cause(params, state, p.z[a]),
        });
    }
    Ok(())
}

/// Why grains overlap by more than [`MAX_OVERLAP`] of a diameter, with the keys that
/// set the contact's stiffness and the time step.
fn overlap_cause(params: &Params, state: &State, z: f64) -> String {
    let s = &params.cfg.settings;
    let stiffness = match s.contact {
        ContactModel::Linear => {
            format!("particles.contact.stiffness = {} N/m", saltus_core::param::number(s.stiffness))
        }
        ContactModel::Hertz => format!("particles.contact.young = {} Pa", saltus_core::param::number(s.young)),
    };
    format!(
        "grains overlap by more than {MAX_OVERLAP} of a diameter at z = {} m, where a soft-sphere contact no longer holds: the contact is too soft for the load ({stiffness}; raise it, or leave particles.contact.stiffness out for the rigid-limit default of the linear law) or the time step {} s lets collisions run through (lower solver.lagrangian.dt_safety = {})",
        saltus_core::param::decimal(z),
        saltus_core::param::number(state.dem.dt()),
        saltus_core::param::number(s.numerics.dt_safety)
    )
}

/// Why a particle at height z outran [`MAX_SPEED`]: carried there by the fluid (a
/// fluid period too long for the explicit coupling, or a driving too strong), or
/// thrown by the contacts (a time step too large for their stiffness).
fn speed_cause(params: &Params, state: &State, z: f64) -> String {
    let u = state.field.velocity(z);
    let at = format!("speed above {MAX_SPEED} m/s at z = {} m", saltus_core::param::decimal(z));
    if u.abs() > 0.5 * MAX_SPEED {
        format!(
            "{at}, where the fluid moves at {} m/s: the driving is too strong or solver.lagrangian.fluid_period = {} s too long for the coupling",
            saltus_core::param::number(u),
            saltus_core::param::number(params.cfg.settings.numerics.fluid_period)
        )
    } else {
        format!(
            "{at}, the fluid there at {} m/s: the contacts threw it, the time step {} s is too large for the contact stiffness (lower solver.lagrangian.dt_safety = {})",
            saltus_core::param::number(u),
            saltus_core::param::number(state.dem.dt()),
            saltus_core::param::number(params.cfg.settings.numerics.dt_safety)
        )
    }
}

/// The pressure gradient -dp/dx at flow time `t` (Pa/m): the steady one and that of
/// `physics.forcing`, if any.
pub(crate) fn pressure_gradient(params: &Params, t: f64) -> f64 {
    let physics = &params.scene.physics;
    match &physics.forcing {
        Some(f) => physics.pressure_gradient + f.gradient(t, params.scene.fluid.density),
        None => physics.pressure_gradient,
    }
}

/// The particles' share of a time-dependent forcing: the streamwise body acceleration
/// of the DEM step that starts now, with the pressure gradient at its start (the step
/// is explicit). Nothing without a forcing.
fn apply_forcing(params: &Params, state: &mut State) {
    let scene = params.scene;
    if scene.physics.forcing.is_none() {
        return;
    }
    let grad = pressure_gradient(params, state.time);
    let p = &scene.physics;
    let body = super::setup::body_acceleration(
        &params.cfg,
        p.gravity,
        p.slope,
        scene.fluid.density,
        scene.particles.density,
        grad,
    );
    state.dem.body[0] = body[0];
}

impl Lagrangian<'_> {
    /// One fluid update: averages, column solve, field refresh, and with `sampled` (the
    /// step's [`sample_due`]) the statistics.
    fn fluid_update(&mut self, sampled: bool) -> Result<(), Breakdown> {
        average(&self.params, &mut self.state, &mut self.work);
        let t0 = Instant::now();
        let tau_f = self.params.cfg.settings.numerics.fluid_period;
        // the fluid's share of a forcing: the column's backward-Euler step to t + tau_f
        // takes the pressure gradient of its end
        let forced = self
            .params
            .scene
            .physics
            .forcing
            .is_some()
            .then(|| pressure_gradient(&self.params, self.state.time + tau_f));
        let State { column, sums, beta, u_p, bed_surface, field, slip, tau_t, time, .. } = &mut self.state;
        if let Some(col) = column.as_mut() {
            let models = ExchangeModels {
                closures: Closures {
                    viscosity: self.params.viscosity,
                    turbulence: self.params.turbulence,
                    wall_friction: self.params.scene.closures.wall_friction.as_deref(),
                },
                drag: self.params.drag,
                hindrance: self.params.hindrance,
                rho_f: self.params.scene.fluid.density,
            };
            let grains = Grains { sums, beta, u_p, bed_surface: *bed_surface };
            step_column(col, &models, &grains, field, slip, tau_t, (*time, tau_f), forced)?;
        }
        let t0 = self.work.stages.lap(stage::COLUMN, t0);
        check(&self.params, &self.state)?;
        let qs = self.state.transport_rate();
        self.state.steady.add(self.state.time, qs);
        self.state.truncation.add(self.state.time, qs);
        if sampled {
            let tau_face: &[f64] = match &self.state.column {
                Some(c) => c.shear_stress(),
                None => &self.work.zero_faces,
            };
            self.state.stats.add(
                &self.state.sums,
                &self.state.field.u,
                &self.state.tau_t,
                &self.state.field.nu_t,
                &self.state.beta,
                tau_face,
                qs,
            );
            sample_granular(&mut self.state);
        }
        self.work.stages.lap(stage::SAMPLING, t0);
        Ok(())
    }

    /// One DEM step of the flow, with the fluid update when it is due, unless `limits`
    /// are reached (`Ok(None)`, no step taken). `Ok(Some(true))` when the fluid was updated
    /// or the state checked (every [`CHECK_STEPS`] steps). `solver.lagrangian.max_steps`
    /// bounds the DEM steps of the whole run, deposition included.
    fn flow_step(&mut self, limits: &Limits) -> Result<Option<bool>, Breakdown> {
        let fluid = self.params.cfg.settings.numerics.fluid;
        let every = self.params.fluid_every;
        if self.state.settle_steps + self.state.steps >= limits.max_steps || self.state.time >= limits.end_time {
            return Ok(None);
        }
        let update = self.state.steps.checked_rem(every) == Some(0);
        // a fluid period of many thousand steps must not leave the state unchecked, nor the
        // driver (progress, Ctrl-C) waiting, for all of them
        let checkpoint = !update && self.state.steps.is_multiple_of(CHECK_STEPS);
        if update && fluid == FluidMode::Off {
            // the state at the start of the period, at its exact time: the first sample is
            // the initial temperature Haff's law starts from
            self.state.stats.cooling.add(self.state.time, self.state.dem.p.temperature(), self.params.haff);
        }
        let sampled = update && sample_due(&self.params, &self.state);
        apply_forcing(&self.params, &mut self.state);
        let granular = sampled && self.state.granular.is_some();
        dem_step(&self.params, &mut self.state, &mut self.work, update && fluid != FluidMode::Off, granular);
        if fluid != FluidMode::Off {
            // eq 14's window: every step's slices (nothing when the scene keeps none)
            let f = &self.state.field;
            self.state.phi_window.add(&self.state.dem.p, f.base, f.dz);
        }
        if update {
            if fluid == FluidMode::Off {
                check(&self.params, &self.state)?;
            } else {
                self.fluid_update(sampled)?;
            }
            if fluid == FluidMode::Off && sampled {
                let t0 = Instant::now();
                dry_sample(&self.params, &mut self.state, &mut self.work);
                self.work.stages.lap(stage::SAMPLING, t0);
            }
        } else if checkpoint {
            check(&self.params, &self.state)?;
        }
        self.state.steps += 1;
        self.state.time = self.state.steps as f64 * self.state.dem.dt();
        Ok(Some(update || checkpoint))
    }

    /// One DEM step of the flow, with the fluid update when it is due: `Ok(true)` when the
    /// fluid was updated or the state checked, `Err` with the ending when the run is over
    /// (its end time or step cap reached, or a breakdown). For tests and benches that step
    /// the flow one DEM step at a time; the driver steps it a fluid period at a time.
    pub fn step_dem(&mut self) -> Result<bool, Ending> {
        let limits = self.limits();
        match self.flow_step(&limits) {
            Ok(Some(checked)) => Ok(checked),
            Ok(None) => Err(limits.reached(&self.progress()).unwrap_or(Ending::EndTime)),
            Err(b) => Err(Ending::Unstable(b)),
        }
    }

    /// DEM steps of the flow up to and including the next fluid update, or up to `limits`;
    /// `Some` when the run ends for its own reasons (steady, a breakdown).
    fn advance(&mut self, limits: &Limits) -> Option<Ending> {
        loop {
            match self.flow_step(limits) {
                Err(b) => return Some(Ending::Unstable(b)),
                Ok(None) => return None,
                Ok(Some(false)) => {}
                Ok(Some(true)) => {
                    let numerics = &self.params.cfg.settings.numerics;
                    if numerics.stop_when_steady && self.state.steady.is_steady() {
                        return Some(Ending::Steady);
                    }
                    if let Some(target) = numerics.target_error {
                        if self.state.truncation.due() && self.state.truncation.reached(target) {
                            return Some(Ending::TargetError);
                        }
                    }
                    return None;
                }
            }
        }
    }

    /// One unit of work of the current phase: a fluid period of the deposition or of the
    /// flow.
    pub(crate) fn unit_of_work(&mut self, limits: &Limits) -> Option<Ending> {
        match self.state.stage {
            Stage::Deposition => self.deposit_period(limits),
            Stage::Flow => self.advance(limits),
        }
    }

    /// Run the deposition to its end (nothing to do without one). `Err` with the ending
    /// when the run ended during it (step cap, breakdown).
    pub fn deposit(&mut self) -> Result<(), Ending> {
        let limits = self.limits();
        while self.state.stage == Stage::Deposition {
            if let Some(e) = self.step(&limits) {
                return Err(e);
            }
            if let Some(e) = limits.reached(&self.progress()) {
                return Err(e);
            }
        }
        Ok(())
    }

    /// Take `state` (a restored checkpoint) as the run's: the workspace sized for it and the
    /// field's derived parts refreshed.
    pub(crate) fn adopt(&mut self, state: State) {
        self.state = state;
        self.state.field.refresh();
        self.state.field.set_bed_threshold(self.params.fluctuation.and_then(|f| f.above_bed()));
        self.work.resize(self.state.field.u.len());
    }
}
