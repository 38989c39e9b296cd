//! The coupled run: deposition, then DEM steps with the fluid column solved every fluid
//! period (Maurin et al. 2015 section II D). The deposition lives in `deposition.rs`, the
//! driver's view of the run in [`super::stepper`].

use std::borrow::Cow;
use std::time::Instant;

use saltus_core::scene::{DragVelocity, Scene};
use saltus_core::{DragLaw, EffectiveViscosity, Error, Hindrance, Turbulence};

use super::averaging::{CellSums, Seen};
use super::config::{Config, FluidMode, Initial};
use super::contact::{ContactLaw, ContactModel};
use super::dem::Dem;
use super::drag::{DragModels, FluidField, FluidForces};
use super::granular::GranularStats;
use super::particles::Particles;
use super::setup::{self, Material};
use super::stats::{Stats, Steady};
use crate::column::{Closures, ColumnParams, Coupling, FluidColumn, Grid, TopBoundary};
use crate::inputs;
use crate::run::{Breakdown, Ending, Place};

/// Particle speed beyond which the run is declared unstable (m/s): far above any
/// bedload or settling velocity, reached only when the time step is too large for the
/// stiffness.
pub const MAX_SPEED: f64 = 100.0;

/// Most DEM steps a scene may ask for (deposition and flow): the top of the range of
/// `solver.lagrangian.max_steps`.
pub const MAX_DEM_STEPS: f64 = 1e15;

/// DEM steps between two checks of the state (and two returns to the driver) when the
/// fluid period is longer: the state is checked at every fluid update and at least this
/// often.
pub const CHECK_STEPS: u64 = 2000;

/// What the run is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub(super) enum Stage {
    /// settling the bed under gravity, fluid at rest
    Deposition,
    /// the flow
    Flow,
}

/// The Lagrangian solver of a scene: the DEM, the fluid column and the statistics. The
/// driver advances it through [`crate::run::Stepper`]; tests and benches read it through
/// the methods below.
pub struct Lagrangian<'a> {
    pub(super) scene: &'a Scene,
    pub(super) cfg: Config,
    pub(super) dem: Dem,
    pub(super) forces: FluidForces,
    pub(super) field: FluidField,
    pub(super) column: Option<FluidColumn>,
    viscosity: &'a dyn EffectiveViscosity,
    turbulence: &'a dyn Turbulence,
    drag: &'a dyn DragLaw,
    hindrance: &'a dyn Hindrance,
    pub(super) fluctuation: Option<&'a dyn saltus_core::Fluctuation>,
    pub(super) sums: CellSums,
    /// fluid velocity averaged over each particle at the drag evaluation of the last fluid
    /// update (m/s), ubar_p of the exact exchange ([`CellSums::accumulate`]); with
    /// `drag_velocity = "centre"`, zeros (unused)
    pub(super) seen: Vec<f64>,
    pub(super) phi: Vec<f64>,
    pub(super) u_p: Vec<f64>,
    pub(super) beta: Vec<f64>,
    pub(super) tau_t: Vec<f64>,
    pub(super) stats: Stats,
    /// the granular fields' sums, when the scene asks for them
    pub(super) granular: Option<GranularStats>,
    pub(super) steady: Steady,
    pub(super) cell_volume: f64,
    pub(super) fluid_every: u64,
    /// time of the flow (after the deposition) (s)
    pub(super) time: f64,
    /// DEM steps of the flow
    pub(super) steps: u64,
    pub(super) stage: Stage,
    /// DEM steps of the deposition taken, and to take
    pub(super) settle_steps: u64,
    pub(super) settle_total: u64,
    /// body acceleration of the flow (the deposition runs without the streamwise pull)
    pub(super) flow_body: [f64; 3],
    pub(super) mat: Material,
    rho_f: f64,
    pub(super) bed_surface: f64,
    /// the ParaView snapshot series, when `solver.lagrangian.vtk_period` > 0 and the
    /// driver gave a folder
    pub(super) vtk: Option<super::vtk::Series>,
    /// why the first snapshot that failed was not written
    pub(super) vtk_error: Option<String>,
    pub(super) next_vtk: f64,
    pub(super) seed: u64,
    pub(super) zero_faces: Vec<f64>,
    pub(super) column_params: Option<ColumnParams>,
    re_free_hindrance: bool,
    /// the pool of `solver.lagrangian.threads`, `None` for the caller's
    pub(super) pool: Option<rayon::ThreadPool>,
    /// wall clock of the flow phase: its start and the time spent up to the last step (s)
    pub(super) flow_started: Option<Instant>,
    pub(super) flow_wall: f64,
    /// wall-clock time of the flow before a restart (s)
    pub(super) flow_wall_before: f64,
    /// Haff's constant sqrt(pi) d / (4 (1 - e^2) phi g0) (s m/s) of a homogeneous cooling
    /// scene ([`super::stats::Cooling`]), `None` for any other
    pub(super) haff: Option<f64>,
}

impl<'a> Lagrangian<'a> {
    /// Build the particles, the walls and the fluid column of `scene`.
    pub fn new(scene: &'a Scene, cfg: Config) -> Result<Self, Error> {
        let file = scene.path.display().to_string();
        let cl = &scene.closures;
        let missing = |family: &str| Error::Invalid(format!("{file}: closures.{family} is not resolved"));
        let drag = cl.drag.as_deref().ok_or_else(|| missing("drag"))?;
        let hindrance = cl.hindrance.as_deref().ok_or_else(|| missing("hindrance"))?;
        let viscosity = cl.viscosity.as_deref().ok_or_else(|| missing("viscosity"))?;
        let turbulence = cl.turbulence.as_deref().ok_or_else(|| missing("turbulence"))?;
        let fluctuation = cl.fluctuation.as_deref().filter(|f| f.is_active());
        if !turbulence.transported().is_empty() && turbulence.as_two_equation().is_none() {
            return Err(Error::Invalid(format!(
                "{file}: closures.turbulence `{}` transports fields the column solver cannot advance; use laminar, mixing_length or k_omega",
                turbulence.name()
            )));
        }
        // the hindrance declares its convention and whether it sees Re_p: nothing probed
        let re_free = !hindrance.depends_on_reynolds();
        let s = &cfg.settings;
        let d = scene.particles.diameter;
        let rho_p = scene.particles.density;
        let mat = Material { d, rho_p };
        let p = setup::initial_particles(&cfg, &mat, scene.seed, &file)?;
        let law = match s.contact {
            ContactModel::Linear => {
                ContactLaw::linear(s.stiffness, s.stiffness * s.tangential_ratio, s.restitution, s.friction)
            }
            ContactModel::Hertz => ContactLaw::hertz(s.young, s.poisson, s.restitution, s.friction),
        }
        .with_normal_force(s.normal_force);
        let m = rho_p * setup::sphere_volume(d);
        let dt = s.numerics.dt_safety * law.contact_time(m, 0.5 * d, rho_p, s.young, s.poisson);
        let body = setup::body_acceleration(
            &cfg,
            scene.physics.gravity,
            scene.physics.slope,
            scene.fluid.density,
            rho_p,
            scene.physics.pressure_gradient,
        );
        let dem = Dem::new(p, setup::make_box(&cfg), law, setup::make_walls(&cfg), body, dt, s.numerics.skin * d)
            .with_cylinders(setup::half_cylinders(&cfg, &mat, scene.seed))
            .with_wall_friction(scene.particles.wall_friction);
        let n = dem.p.len();
        let mut forces = FluidForces::new(n, scene.seed, scene.fluid.density, scene.fluid.viscosity, rho_p);
        forces.fallback_period = s.numerics.fluid_period;
        let cells = cfg.domain.cells;
        // without a column and without samples the grid only sizes the drag's cell look-up
        let columnless = s.numerics.fluid == FluidMode::Off && !s.numerics.takes_samples();
        let height = if columnless
            || cfg.settings.numerics.bottom == super::config::Bottom::Periodic
            || cfg.column_height() <= 0.0
        {
            1.0
        } else {
            cfg.column_height()
        };
        let grid = Grid::uniform(cells, height)
            .map_err(|e| Error::Invalid(format!("{file}: key `solver.lagrangian.cells`: {e}")))?;
        let dz = grid.dz()[0];
        let mut column_params = None;
        let column = if s.numerics.fluid == FluidMode::Coupled {
            let params = ColumnParams {
                density: scene.fluid.density,
                viscosity: scene.fluid.viscosity,
                diameter: d,
                gravity_x: scene.physics.gravity * scene.physics.slope,
                pressure_gradient: scene.physics.pressure_gradient,
                top: match scene.domain.top {
                    saltus_core::scene::Top::Lid => TopBoundary::Lid { velocity: scene.domain.lid_velocity },
                    saltus_core::scene::Top::Symmetry => TopBoundary::Symmetry,
                    saltus_core::scene::Top::FreeSurface => TopBoundary::FreeSurface,
                },
                relaxation: 0.5,
                particle_density: scene.particles.density,
                gravity_normal: scene.physics.gravity * (1.0 - scene.physics.slope * scene.physics.slope).sqrt(),
                // u* of the flow above the bed, as in the Eulerian solver (k-omega's rough
                // wall and in-bed omega): the bed carries no part of the driving's stress
                friction_velocity: Some(crate::column::turbulence::friction_velocity(
                    scene.physics.gravity * scene.physics.slope + scene.physics.pressure_gradient / scene.fluid.density,
                    cfg.domain.water_depth,
                )),
                // the scene is refused at load with a wall friction and no walls
                side_walls: scene
                    .closures
                    .wall_friction
                    .is_some()
                    .then_some(crate::column::SideWalls { width: cfg.domain.width }),
            };
            column_params = Some(params);
            Some(FluidColumn::new(grid, params)?)
        } else {
            None
        };
        // the steps the scene asks, known before the first: a time step that underflows
        // (dt_safety or a stiffness at the end of their ranges) would otherwise make the
        // deposition and the flow crawl for ever
        let asked = (s.settle_time + s.numerics.end_time) / dt;
        if dt.is_nan() || dt <= 0.0 || asked.is_nan() || asked > MAX_DEM_STEPS {
            let stiffness = match s.contact {
                ContactModel::Linear => "particles.contact.stiffness",
                ContactModel::Hertz => "particles.contact.young",
            };
            return Err(Error::Key {
                file: scene.path.clone(),
                key: "solver.lagrangian.dt_safety".into(),
                message: format!(
                    "{} with {stiffness} gives a DEM time step of {} s, and solver.lagrangian.settle_time + end_time = {} s then takes {} steps, more than {}; raise dt_safety, soften the contact or shorten the run",
                    saltus_core::param::number(s.numerics.dt_safety),
                    saltus_core::param::number(dt),
                    saltus_core::param::number(s.settle_time + s.numerics.end_time),
                    saltus_core::param::number(asked),
                    saltus_core::param::number(MAX_DEM_STEPS),
                ),
            });
        }
        let fluid_every = ((s.numerics.fluid_period / dt).round() as u64).max(1);
        let pool = super::stepper::pool(s.numerics.threads, &scene.path)?;
        let deposit = cfg.settings.numerics.initial == Initial::Bed;
        let settle_total = if deposit { (s.settle_time / dt).ceil() as u64 } else { 0 };
        let flow_body = dem.body;
        let mut dem = dem;
        if deposit {
            // deposit without the streamwise pull: the bed forms at rest
            dem.body[0] = 0.0;
        }
        let v = |x: f64| vec![x; cells];
        let haff = haff_constant(&cfg, &dem.p, flow_body, d);
        let mut field = FluidField::at_rest(cells, dz, cfg.rough_height(d));
        field.set_bed_threshold(fluctuation.and_then(|f| f.above_bed()));
        Ok(Self {
            haff,
            scene,
            field,
            column,
            viscosity,
            turbulence,
            drag,
            hindrance,
            fluctuation,
            re_free_hindrance: re_free,
            sums: CellSums::new(cells),
            seen: vec![0.0; n],
            phi: v(0.0),
            u_p: v(0.0),
            beta: v(0.0),
            tau_t: v(0.0),
            stats: Stats::new(cells),
            granular: s
                .numerics
                .granular_fields
                .unwrap_or(s.numerics.fluid != FluidMode::Off)
                .then(|| GranularStats::new(cells)),
            steady: Steady::new(s.numerics.steady_window, s.numerics.steady_tolerance, s.numerics.steady_windows),
            cell_volume: cfg.domain.length * cfg.domain.width * dz,
            fluid_every,
            time: 0.0,
            steps: 0,
            stage: if deposit { Stage::Deposition } else { Stage::Flow },
            settle_steps: 0,
            settle_total,
            flow_body,
            pool,
            flow_started: None,
            flow_wall: 0.0,
            flow_wall_before: 0.0,
            mat,
            rho_f: scene.fluid.density,
            bed_surface: cfg.bed_surface(),
            vtk: None,
            vtk_error: None,
            next_vtk: 0.0,
            seed: scene.seed,
            zero_faces: vec![0.0; cells + 1],
            column_params,
            dem,
            forces,
            cfg,
        })
    }

    fn models(&self) -> DragModels<'a> {
        DragModels {
            drag: self.drag,
            hindrance: self.hindrance,
            fluctuation: self.fluctuation,
            velocity: self.cfg.settings.numerics.drag_velocity,
        }
    }

    /// One DEM step with the fluid force of the current fluid field; with `sampled`, the
    /// step takes the contact sums of the granular fields.
    pub(super) fn dem_step(&mut self, all: bool, sampled: bool) {
        if self.cfg.settings.numerics.fluid != FluidMode::Off {
            let upto = if all { self.dem.p.len() } else { self.dem.p.n_mobile };
            let models = self.models();
            let dt = self.dem.dt();
            self.forces.evaluate(&self.dem.p, &self.field, &models, dt, upto, &mut self.dem.ext);
            if all && models.velocity == DragVelocity::SphereAverage {
                // the exact exchange needs the fluid velocity each grain's drag saw,
                // before the step moves it
                let p = &self.dem.p;
                self.seen.resize(p.len(), 0.0);
                for ((s, &z), &r) in self.seen.iter_mut().zip(&p.z).zip(&p.radius) {
                    *s = self.field.sphere_velocity(z, r);
                }
            }
        }
        let slices = sampled.then(|| self.slices());
        self.dem.step_sampled(slices);
    }

    /// Average the particles on the cells and refresh phi (and the hindrance convention)
    /// the particles see.
    pub(super) fn average(&mut self) {
        let (k, urx) = (&self.forces.k, &self.forces.urx);
        let seen = match self.cfg.settings.numerics.drag_velocity {
            DragVelocity::Centre => Seen::Centre,
            DragVelocity::SphereAverage => {
                // one per particle even where no drag was evaluated (a dry run's samples)
                self.seen.resize(self.dem.p.len(), 0.0);
                Seen::SphereAverage(&self.seen)
            }
        };
        self.sums.accumulate(&self.dem.p, self.field.base, self.field.dz, k, urx, seen);
        let u_f: &[f64] = match &self.column {
            Some(c) => c.velocity(),
            None => &self.field.u,
        };
        self.sums.coupling(self.cell_volume, u_f, &mut self.phi, &mut self.u_p, &mut self.beta);
        for (c, &phi) in self.phi.iter().enumerate() {
            self.field.phi[c] = phi.min(0.99);
            self.field.re_ratio[c] = self.hindrance.reynolds_convention().ratio(phi.min(0.99));
        }
        self.field.set_bed_threshold(self.fluctuation.and_then(|f| f.above_bed()));
        if self.re_free_hindrance {
            let n = self.field.phi.len();
            self.field.hindrance.resize(n, 1.0);
            // Re_p does not matter for such a closure
            self.hindrance.factor_batch(&self.field.phi, &self.zero_faces[..n], &mut self.field.hindrance);
        }
    }

    /// Time of the current phase (s): of the deposition, then of the flow.
    pub(super) fn phase_time(&self) -> f64 {
        match self.stage {
            Stage::Deposition => self.settle_steps as f64 * self.dem.dt(),
            Stage::Flow => self.time,
        }
    }

    /// First non-finite or runaway particle.
    pub(super) fn check(&self) -> Result<(), Breakdown> {
        let time = self.phase_time();
        if let Some((a, field, value)) = self.dem.first_non_finite() {
            return Err(Breakdown {
                time,
                place: Place::Particle { index: a },
                field: Cow::Borrowed(field),
                value,
                reason: "not finite".into(),
            });
        }
        let p = &self.dem.p;
        for a in 0..p.n_mobile {
            let s2 = p.vx[a] * p.vx[a] + p.vy[a] * p.vy[a] + p.vz[a] * p.vz[a];
            if s2 > MAX_SPEED * MAX_SPEED {
                return Err(Breakdown {
                    time,
                    place: Place::Particle { index: a },
                    field: Cow::Borrowed("|v|"),
                    value: s2.sqrt(),
                    reason: self.speed_cause(p.z[a]),
                });
            }
        }
        Ok(())
    }

    /// Why a particle at height z outran [`MAX_SPEED`]: carried there by the fluid (a
    /// fluid period too long for the explicit coupling, or a driving too strong), or
    /// thrown by the contacts (a time step too large for their stiffness).
    fn speed_cause(&self, z: f64) -> String {
        let u = self.field.velocity(z);
        let at = format!("speed above {MAX_SPEED} m/s at z = {} m", saltus_core::param::decimal(z));
        if u.abs() > 0.5 * MAX_SPEED {
            format!(
                "{at}, where the fluid moves at {} m/s: the driving is too strong or solver.lagrangian.fluid_period = {} s too long for the coupling",
                saltus_core::param::number(u),
                saltus_core::param::number(self.cfg.settings.numerics.fluid_period)
            )
        } else {
            format!(
                "{at}, the fluid there at {} m/s: the contacts threw it, the time step {} s is too large for the contact stiffness (lower solver.lagrangian.dt_safety = {})",
                saltus_core::param::number(u),
                saltus_core::param::number(self.dem.dt()),
                saltus_core::param::number(self.cfg.settings.numerics.dt_safety)
            )
        }
    }

    /// One fluid update: averages, column solve, field refresh, statistics.
    fn fluid_update(&mut self) -> Result<(), Breakdown> {
        self.average();
        let tau_f = self.cfg.settings.numerics.fluid_period;
        if let Some(col) = self.column.as_mut() {
            let coupling = Coupling { phi: &self.field.phi, beta: &self.beta, u_p: &self.u_p };
            let closures = Closures {
                viscosity: self.viscosity,
                turbulence: self.turbulence,
                wall_friction: self.scene.closures.wall_friction.as_deref(),
            };
            if let Err(e) = col.step(tau_f, &coupling, &closures) {
                return Err(Breakdown {
                    time: self.time,
                    place: Place::Column,
                    field: Cow::Borrowed("u_f"),
                    value: f64::NAN,
                    reason: e.to_string(),
                });
            }
            // a runaway column (a fluid period far beyond the particles' response time
            // leaves the drag no hold on it) is stopped here with its cause, before the
            // particles it would fling blow up
            if let Some((c, &u)) = col.velocity().iter().enumerate().find(|(_, u)| u.is_nan() || u.abs() > MAX_SPEED) {
                return Err(Breakdown {
                    time: self.time,
                    place: Place::Cell { index: c, z: col.grid().centres()[c] },
                    field: Cow::Borrowed("u_f"),
                    value: u,
                    reason: format!(
                        "fluid velocity above {MAX_SPEED} m/s: the driving is too strong or solver.lagrangian.fluid_period = {} s too long for the coupling",
                        saltus_core::param::number(tau_f)
                    ),
                });
            }
            self.field.set_velocity(col.velocity());
            self.field.nu_t.copy_from_slice(col.eddy_viscosity());
            if let Some((k, omega)) = col.k_omega() {
                let [kf, wf] = &mut self.field.k_omega;
                kf.clear();
                kf.extend_from_slice(k);
                wf.clear();
                wf.extend_from_slice(omega);
            }
            for ((r, &nu), &g) in self.field.reynolds.iter_mut().zip(col.eddy_viscosity()).zip(col.shear_rate()) {
                *r = inputs::reynolds_stress(nu, g);
            }
            col.reynolds_stress(&mut self.tau_t);
            let grid = col.grid();
            let bed = inputs::bed_surface(grid.centres(), &self.field.phi, self.bed_surface);
            self.field.scales = inputs::flow_scales(grid.centres(), grid.dz(), col.velocity(), grid.height(), bed);
        }
        self.check()?;
        let qs: f64 = self.sums.v[0].iter().sum::<f64>() / (self.cell_volume / self.field.dz);
        self.steady.add(self.time, qs);
        if self.time >= self.cfg.settings.numerics.stats_start {
            let tau_face: &[f64] = match &self.column {
                Some(c) => c.shear_stress(),
                None => &self.zero_faces,
            };
            self.stats.add(&self.sums, &self.field.u, &self.tau_t, &self.field.nu_t, &self.beta, tau_face, qs);
            self.sample_granular();
        }
        Ok(())
    }

    /// One DEM step of the flow, with the fluid update when it is due. `Ok(true)` when the
    /// fluid was updated or the state checked (every [`CHECK_STEPS`] steps), `Err` with the ending when the run is over. `solver.lagrangian.max_steps`
    /// bounds the DEM steps of the whole run, deposition included.
    pub fn step_dem(&mut self) -> Result<bool, Ending> {
        let s = &self.cfg.settings;
        let (every, fluid) = (self.fluid_every, s.numerics.fluid);
        if self.settle_steps + self.steps >= s.numerics.max_steps {
            return Err(Ending::MaxSteps);
        }
        if self.time >= s.numerics.end_time {
            return Err(Ending::EndTime);
        }
        let update = self.steps.checked_rem(every) == Some(0);
        // a fluid period of many thousand steps must not leave the state unchecked, nor the
        // driver (progress, Ctrl-C) waiting, for all of them
        let checkpoint = !update && self.steps.is_multiple_of(CHECK_STEPS);
        if update && fluid == FluidMode::Off {
            // the state at the start of the period, at its exact time: the first sample is
            // the initial temperature Haff's law starts from
            self.stats.cooling.add(self.time, self.dem.p.temperature(), self.haff);
        }
        let sampled = update && self.sample_due();
        self.dem_step(update && fluid != FluidMode::Off, sampled && self.granular.is_some());
        if update {
            let r = if fluid == FluidMode::Off { self.check() } else { self.fluid_update() };
            r.map_err(Ending::Unstable)?;
            if fluid == FluidMode::Off && sampled {
                self.dry_sample();
            }
            if self.vtk.is_some() && self.time >= self.next_vtk {
                self.write_vtk();
                let period = self.cfg.settings.numerics.vtk_period;
                self.next_vtk += period;
                if self.next_vtk <= self.time {
                    // behind the clock (a restart that switched the snapshots on, or a
                    // period shorter than the fluid's): the next period boundary after
                    // now, never one snapshot per update to catch up
                    self.next_vtk += ((self.time - self.next_vtk) / period).floor().min(1e15) * period + period;
                }
            }
        } else if checkpoint {
            self.check().map_err(Ending::Unstable)?;
        }
        self.steps += 1;
        self.time = self.steps as f64 * self.dem.dt();
        Ok(update || checkpoint)
    }

    /// DEM steps of the flow up to and including the next fluid update; `Some` when the
    /// run is over.
    pub(super) fn advance(&mut self) -> Option<Ending> {
        loop {
            match self.step_dem() {
                Err(e) => return Some(e),
                Ok(false) => {}
                Ok(true) => {
                    if self.cfg.settings.numerics.stop_when_steady && self.steady.is_steady() {
                        return Some(Ending::Steady);
                    }
                    return None;
                }
            }
        }
    }

    /// Fluid density (kg/m^3).
    pub fn fluid_density(&self) -> f64 {
        self.rho_f
    }
}

/// sqrt(pi) d / (4 (1 - e^2) phi g0), Carnahan-Starling g0, for the scenes whose
/// temperature Haff's law describes (see [`super::stats::Cooling`]): an inelastic,
/// frictionless gas with neither fluid nor body force in a triply periodic box.
fn haff_constant(cfg: &Config, p: &Particles, body: [f64; 3], d: f64) -> Option<f64> {
    let s = &cfg.settings;
    let n = &s.numerics;
    let homogeneous = n.fluid == FluidMode::Off
        && n.initial == Initial::Gas
        && n.bottom == super::config::Bottom::Periodic
        && !n.side_walls
        && body == [0.0; 3]
        && s.friction == 0.0
        && s.restitution < 1.0;
    if !homogeneous {
        return None;
    }
    let volume = cfg.domain.length * cfg.domain.width * n.height;
    let phi = p.n_mobile as f64 * setup::sphere_volume(d) / volume;
    let g0 = (1.0 - 0.5 * phi) / (1.0 - phi).powi(3);
    let e = s.restitution;
    crate::output::finite(std::f64::consts::PI.sqrt() * d / (4.0 * (1.0 - e * e) * phi * g0)).filter(|h| *h > 0.0)
}
