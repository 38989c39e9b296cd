//! The coupled run: deposition, then DEM steps with the fluid column solved every fluid
//! period (Maurin et al. 2015 section II D).

use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_core::{DragLaw, EffectiveViscosity, Error, Hindrance, Turbulence};

use super::averaging::CellSums;
use super::config::{Config, FluidMode, Initial};
use super::contact::{ContactLaw, ContactModel};
use super::dem::Dem;
use super::drag::{DragModels, FluidField, FluidForces};
use super::setup::{self, Material};
use super::stats::{Stats, Steady};
use crate::column::{Closures, ColumnParams, Coupling, FluidColumn, Grid, TopBoundary};
use crate::eulerian::Progress;

/// Where and why a run stopped: time, particle or cell, field.
#[derive(Clone, Debug, PartialEq)]
pub struct Breakdown {
    /// simulated time (s)
    pub time: f64,
    /// what went bad: `particle 12`, `cell 40 (z = 0.01 m)`
    pub location: String,
    /// the field
    pub field: String,
    /// its value
    pub value: f64,
    /// why
    pub reason: String,
}

impl std::fmt::Display for Breakdown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "t = {:.6} s: {} = {:e} at {}: {}", self.time, self.field, self.value, self.location, self.reason)
    }
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    /// the transport rate is steady and `stop_when_steady` is set
    Steady,
    /// end time reached
    EndTime,
    /// step cap reached
    MaxSteps,
    /// a particle or a cell went bad
    Unstable(Breakdown),
}

/// Particle speed beyond which the run is declared unstable (m/s): far above any
/// bedload or settling velocity, reached only when the time step is too large for the
/// stiffness.
pub const MAX_SPEED: f64 = 100.0;

/// The Lagrangian solver of a scene.
pub struct Lagrangian<'a> {
    cfg: Config,
    /// DEM state
    pub dem: Dem,
    /// drag state
    pub forces: FluidForces,
    /// fluid seen by the particles
    pub field: FluidField,
    column: Option<FluidColumn>,
    viscosity: &'a dyn EffectiveViscosity,
    turbulence: &'a dyn Turbulence,
    drag: &'a dyn DragLaw,
    hindrance: &'a dyn Hindrance,
    fluctuation: Option<&'a dyn saltus_core::Fluctuation>,
    sums: CellSums,
    phi: Vec<f64>,
    u_p: Vec<f64>,
    beta: Vec<f64>,
    tau_t: Vec<f64>,
    stats: Stats,
    steady: Steady,
    cell_volume: f64,
    fluid_every: u64,
    /// time of the flow (after the deposition) (s)
    time: f64,
    /// DEM steps of the flow
    steps: u64,
    /// DEM steps of the deposition
    pub settle_steps: u64,
    mat: Material,
    rho_f: f64,
    bed_surface: f64,
    vtk_dir: Option<PathBuf>,
    vtk_count: usize,
    next_vtk: f64,
    seed: u64,
    zero_faces: Vec<f64>,
    column_params: Option<ColumnParams>,
    re_free_hindrance: bool,
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
        };
        let m = rho_p * setup::sphere_volume(d);
        let dt = s.dt_safety * law.contact_time(m, 0.5 * d, rho_p, s.young, s.poisson);
        let body = setup::body_acceleration(
            &cfg,
            scene.physics.gravity,
            scene.physics.slope,
            scene.fluid.density,
            rho_p,
            scene.physics.pressure_gradient,
        );
        let dem = Dem::new(p, setup::make_box(&cfg), law, setup::make_walls(&cfg), body, dt, s.skin * d);
        let n = dem.p.len();
        let mut forces = FluidForces::new(n, scene.seed, scene.fluid.density, scene.fluid.viscosity, rho_p);
        forces.fallback_period = s.fluid_period;
        let cells = cfg.domain.cells;
        let height = if s.fluid == FluidMode::Off || cfg.domain.bottom == super::config::Bottom::Periodic {
            1.0
        } else {
            cfg.column_height()
        };
        let grid = Grid::uniform(cells, height).map_err(|e| Error::Invalid(format!("{file}: domain.cells: {e}")))?;
        let dz = grid.dz()[0];
        let mut column_params = None;
        let column = if s.fluid == FluidMode::Coupled {
            let params = ColumnParams {
                density: scene.fluid.density,
                viscosity: scene.fluid.viscosity,
                diameter: d,
                gravity_x: scene.physics.gravity * scene.physics.slope,
                pressure_gradient: scene.physics.pressure_gradient,
                top: TopBoundary::FreeSurface,
                relaxation: 0.5,
                particle_density: scene.particles.density,
                gravity_normal: scene.physics.gravity * (1.0 - scene.physics.slope * scene.physics.slope).sqrt(),
                // the driving over the whole column (k-omega's rough wall and in-bed omega)
                friction_velocity: None,
            };
            column_params = Some(params);
            Some(FluidColumn::new(grid, params)?)
        } else {
            None
        };
        let fluid_every = ((s.fluid_period / dt).round() as u64).max(1);
        let v = |x: f64| vec![x; cells];
        Ok(Self {
            field: FluidField::at_rest(cells, dz, cfg.rough_height(d)),
            column,
            viscosity,
            turbulence,
            drag,
            hindrance,
            fluctuation,
            re_free_hindrance: re_free,
            sums: CellSums::new(cells),
            phi: v(0.0),
            u_p: v(0.0),
            beta: v(0.0),
            tau_t: v(0.0),
            stats: Stats::new(cells),
            steady: Steady::new(s.steady_window, s.steady_tolerance, s.steady_windows),
            cell_volume: cfg.domain.length * cfg.domain.width * dz,
            fluid_every,
            time: 0.0,
            steps: 0,
            settle_steps: 0,
            mat,
            rho_f: scene.fluid.density,
            bed_surface: cfg.bed_surface(),
            vtk_dir: None,
            vtk_count: 0,
            next_vtk: 0.0,
            seed: scene.seed,
            zero_faces: vec![0.0; cells + 1],
            column_params,
            dem,
            forces,
            cfg,
        })
    }

    /// Write VTK particle snapshots into `dir` every `solver.vtk_period` (if > 0).
    pub fn set_vtk_dir(&mut self, dir: &Path) {
        if self.cfg.settings.vtk_period > 0.0 {
            self.vtk_dir = Some(dir.to_path_buf());
        }
    }

    /// Configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }
    /// Time of the flow (s), after the deposition.
    pub fn time(&self) -> f64 {
        self.time
    }
    /// DEM steps of the flow.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// DEM time step (s).
    pub fn dt(&self) -> f64 {
        self.dem.dt
    }
    /// Mobile particles.
    pub fn mobile(&self) -> usize {
        self.dem.p.n_mobile
    }
    /// Fluid cell height (m).
    pub fn dz(&self) -> f64 {
        self.field.dz
    }
    /// Slice volume A dz (m^3).
    pub fn cell_volume(&self) -> f64 {
        self.cell_volume
    }
    /// Running statistics.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }
    /// Steady-state test.
    pub fn steady(&self) -> &Steady {
        &self.steady
    }
    /// The fluid column, when coupled.
    pub fn column(&self) -> Option<&FluidColumn> {
        self.column.as_ref()
    }
    /// Nominal bed surface above the column bottom (m).
    pub fn bed_surface(&self) -> f64 {
        self.bed_surface
    }
    /// Particle diameter and density.
    pub fn material(&self) -> Material {
        self.mat
    }

    fn models(&self) -> DragModels<'a> {
        DragModels { drag: self.drag, hindrance: self.hindrance, fluctuation: self.fluctuation }
    }

    /// One DEM step with the fluid force of the current fluid field.
    fn dem_step(&mut self, all: bool) {
        if self.cfg.settings.fluid != FluidMode::Off {
            let upto = if all { self.dem.p.len() } else { self.dem.p.n_mobile };
            let models = self.models();
            self.forces.evaluate(&self.dem.p, &self.field, &models, self.dem.dt, upto, &mut self.dem.ext);
        }
        self.dem.step();
    }

    /// Average the particles on the cells and refresh phi (and the hindrance convention)
    /// the particles see.
    fn average(&mut self) {
        self.sums.accumulate(&self.dem.p, self.field.base, self.field.dz, &self.forces.k, &self.forces.urx);
        let u_f: &[f64] = match &self.column {
            Some(c) => c.velocity(),
            None => &self.field.u,
        };
        self.sums.coupling(self.cell_volume, u_f, &mut self.phi, &mut self.u_p, &mut self.beta);
        for (c, &phi) in self.phi.iter().enumerate() {
            self.field.phi[c] = phi.min(0.99);
            self.field.re_ratio[c] = self.hindrance.reynolds_convention().ratio(phi.min(0.99));
        }
        if self.re_free_hindrance {
            let n = self.field.phi.len();
            self.field.hindrance.resize(n, 1.0);
            // Re_p does not matter for such a closure
            self.hindrance.factor_batch(&self.field.phi, &self.zero_faces[..n], &mut self.field.hindrance);
        }
    }

    /// Deposition under gravity with the fluid at rest for `solver.settle_time`; with a
    /// rough bottom, the lowest particles are then removed or fixed. Only for
    /// `initial = "bed"`; other starts keep their particles.
    pub fn settle(&mut self) -> Result<(), Breakdown> {
        if self.cfg.domain.initial != Initial::Bed {
            return Ok(());
        }
        let n_steps = (self.cfg.settings.settle_time / self.dem.dt).ceil() as u64;
        let every = self.fluid_every;
        let saved_body = self.dem.body;
        // deposit without the streamwise pull: the bed forms at rest
        self.dem.body[0] = 0.0;
        for k in 0..n_steps {
            let update = k.checked_rem(every) == Some(0) && self.cfg.settings.fluid != FluidMode::Off;
            self.dem_step(update);
            if update {
                self.average();
                self.check()?;
            }
        }
        self.dem.body = saved_body;
        self.settle_steps = n_steps;
        if self.cfg.domain.bottom == super::config::Bottom::Rough {
            let (_, removed, fixed) = setup::bed_counts(&self.cfg, &self.mat);
            self.dem.p = setup::fix_rough_layer(&self.dem.p, removed, fixed, self.mat.rho_p);
        } else {
            for v in [&mut self.dem.p.vx, &mut self.dem.p.vy, &mut self.dem.p.vz] {
                v.fill(0.0);
            }
            for v in [&mut self.dem.p.wx, &mut self.dem.p.wy, &mut self.dem.p.wz] {
                v.fill(0.0);
            }
        }
        self.dem.reset_topology();
        if self.cfg.domain.surface == super::config::Surface::Deposit && self.cfg.settings.fluid != FluidMode::Off {
            self.fit_column_to_deposit()?;
        }
        let n = self.dem.p.len();
        let fallback = self.forces.fallback_period;
        self.forces = FluidForces::new(n, self.forces_seed(), self.forces.rho_f, self.forces.nu_f, self.mat.rho_p);
        self.forces.fallback_period = fallback;
        self.dem.time = 0.0;
        Ok(())
    }

    /// Surface of the deposit above the column bottom (m): the highest level where the
    /// packing, averaged over one diameter, is half its largest such average.
    pub fn deposit_surface(&mut self) -> f64 {
        let d = self.mat.d;
        let dz = self.field.dz;
        let n = self.sums.vol.len();
        self.sums.accumulate(&self.dem.p, self.field.base, dz, &self.forces.k, &self.forces.urx);
        let w = ((d / dz).round() as usize).max(1);
        let mut best: f64 = 0.0;
        let mut level = None;
        let mean: Vec<f64> = (0..n)
            .map(|c| {
                let (lo, hi) = (c.saturating_sub(w / 2), (c + w / 2 + 1).min(n));
                self.sums.vol[lo..hi].iter().sum::<f64>() / ((hi - lo) as f64 * self.cell_volume)
            })
            .collect();
        for &m in &mean {
            best = best.max(m);
        }
        for c in (0..n).rev() {
            if mean[c] >= 0.5 * best {
                level = Some((c as f64 + 0.5) * dz);
                break;
            }
        }
        level.unwrap_or(self.bed_surface)
    }

    /// Put the free surface `water_depth` above the deposit: a new column of the same
    /// cell size (before the flow starts; it allocates).
    fn fit_column_to_deposit(&mut self) -> Result<(), Breakdown> {
        let surface = self.deposit_surface();
        let dz = self.field.dz;
        let height = surface + self.cfg.domain.water_depth;
        let cells = ((height / dz).round() as usize).max(2);
        let fail = |reason: String| Breakdown {
            time: 0.0,
            location: "fluid column".into(),
            field: "height".into(),
            value: height,
            reason,
        };
        let grid = Grid::uniform(cells, height).map_err(|e| fail(e.to_string()))?;
        let dz = grid.dz()[0];
        if let Some(params) = self.column_params {
            self.column = Some(FluidColumn::new(grid, params).map_err(|e| fail(e.to_string()))?);
        }
        let base = self.field.base;
        self.field = FluidField::at_rest(cells, dz, base);
        self.sums = CellSums::new(cells);
        let v = |x: f64| vec![x; cells];
        self.phi = v(0.0);
        self.u_p = v(0.0);
        self.beta = v(0.0);
        self.tau_t = v(0.0);
        self.stats = Stats::new(cells);
        self.zero_faces = vec![0.0; cells + 1];
        self.cell_volume = self.cfg.domain.length * self.cfg.domain.width * dz;
        self.bed_surface = surface;
        Ok(())
    }

    fn forces_seed(&self) -> u64 {
        self.seed
    }

    /// First non-finite or runaway particle.
    fn check(&self) -> Result<(), Breakdown> {
        if let Some((a, field, value)) = self.dem.first_non_finite() {
            return Err(Breakdown {
                time: self.time,
                location: format!("particle {a}"),
                field: field.into(),
                value,
                reason: "not finite".into(),
            });
        }
        let p = &self.dem.p;
        for a in 0..p.n_mobile {
            let s2 = p.vx[a] * p.vx[a] + p.vy[a] * p.vy[a] + p.vz[a] * p.vz[a];
            if s2 > MAX_SPEED * MAX_SPEED {
                return Err(Breakdown {
                    time: self.time,
                    location: format!("particle {a} (z = {:.6} m)", p.z[a]),
                    field: "|v|".into(),
                    value: s2.sqrt(),
                    reason: format!(
                        "speed above {MAX_SPEED} m/s: the time step is too large for the contact stiffness (lower solver.dt_safety)"
                    ),
                });
            }
        }
        Ok(())
    }

    /// One fluid update: averages, column solve, field refresh, statistics.
    fn fluid_update(&mut self) -> Result<(), Breakdown> {
        self.average();
        let tau_f = self.cfg.settings.fluid_period;
        if let Some(col) = self.column.as_mut() {
            let coupling = Coupling { phi: &self.field.phi, beta: &self.beta, u_p: &self.u_p };
            let closures = Closures { viscosity: self.viscosity, turbulence: self.turbulence };
            if let Err(e) = col.step(tau_f, &coupling, &closures) {
                return Err(Breakdown {
                    time: self.time,
                    location: "fluid column".into(),
                    field: "u_f".into(),
                    value: f64::NAN,
                    reason: e.to_string(),
                });
            }
            self.field.u.copy_from_slice(col.velocity());
            self.field.nu_t.copy_from_slice(col.eddy_viscosity());
            if let Some((k, omega)) = col.k_omega() {
                let [kf, wf] = &mut self.field.k_omega;
                kf.clear();
                kf.extend_from_slice(k);
                wf.clear();
                wf.extend_from_slice(omega);
            }
            for ((r, &nu), &g) in self.field.reynolds.iter_mut().zip(col.eddy_viscosity()).zip(col.shear_rate()) {
                *r = (nu * g).max(0.0);
            }
            col.reynolds_stress(&mut self.tau_t);
            let zc = col.grid().centres();
            // bed surface: the highest cell at least half as packed as the densest one (the
            // nominal surface before any particle is there)
            let dense = self.field.phi.iter().fold(0.0f64, |a, &b| a.max(b));
            let bed = match self.field.phi.iter().rposition(|&f| dense > 0.1 && f >= 0.5 * dense) {
                Some(c) => zc[c],
                None => self.bed_surface,
            };
            let (mut sum, mut count) = (0.0, 0usize);
            for (&z, &u) in zc.iter().zip(col.velocity()) {
                if z > bed {
                    sum += u;
                    count += 1;
                }
            }
            self.field.scales.depth = col.grid().height() - bed;
            self.field.scales.bulk_velocity = if count > 0 { sum / count as f64 } else { 0.0 };
        }
        self.check()?;
        let qs: f64 = self.sums.v[0].iter().sum::<f64>() / (self.cell_volume / self.field.dz);
        self.steady.add(self.time, qs);
        if self.time >= self.cfg.settings.stats_start {
            let tau_face: &[f64] = match &self.column {
                Some(c) => c.shear_stress(),
                None => &self.zero_faces,
            };
            self.stats.add(&self.sums, &self.field.u, &self.tau_t, &self.field.nu_t, &self.beta, tau_face);
        }
        Ok(())
    }

    /// Deposition (see [`Lagrangian::settle`]) and the start of the fluctuation clocks.
    pub fn start(&mut self) -> Result<(), Breakdown> {
        self.settle()?;
        self.forces.restart_fluctuations();
        self.next_vtk = 0.0;
        Ok(())
    }

    /// Progress at the last fluid update.
    pub fn progress(&self) -> Progress {
        Progress {
            time: self.time,
            end_time: self.cfg.settings.end_time,
            steps: self.steps as usize,
            dt: self.dem.dt,
            residual: self.steady.change,
        }
    }

    /// One DEM step of the flow, with the fluid update when it is due. `Ok(true)` when the
    /// fluid was updated, `Err` with the ending when the run is over.
    pub fn step(&mut self) -> Result<bool, Ending> {
        let s = &self.cfg.settings;
        let (every, fluid) = (self.fluid_every, s.fluid);
        if self.steps >= s.max_steps {
            return Err(Ending::MaxSteps);
        }
        if self.time >= s.end_time {
            return Err(Ending::EndTime);
        }
        let update = self.steps.checked_rem(every) == Some(0);
        self.dem_step(update && fluid != FluidMode::Off);
        if update {
            let r = if fluid == FluidMode::Off { self.check() } else { self.fluid_update() };
            r.map_err(Ending::Unstable)?;
            if self.vtk_dir.is_some() && self.time >= self.next_vtk {
                self.write_vtk();
                self.next_vtk += self.cfg.settings.vtk_period;
            }
        }
        self.steps += 1;
        self.time = self.steps as f64 * self.dem.dt;
        Ok(update)
    }

    /// DEM steps up to and including the next fluid update; `Some` when the run is over.
    pub fn advance(&mut self) -> Option<Ending> {
        loop {
            match self.step() {
                Err(e) => return Some(e),
                Ok(false) => {}
                Ok(true) => {
                    if self.cfg.settings.stop_when_steady && self.steady.is_steady() {
                        return Some(Ending::Steady);
                    }
                    return None;
                }
            }
        }
    }

    /// Run the flow to the end time (or steady state), calling `observer` after every fluid
    /// update; it may stop the run by returning false.
    pub fn run(&mut self, observer: &mut dyn FnMut(&Progress) -> bool) -> Ending {
        if let Err(b) = self.start() {
            return Ending::Unstable(b);
        }
        loop {
            if let Some(e) = self.advance() {
                return e;
            }
            if !observer(&self.progress()) {
                return Ending::EndTime;
            }
        }
    }

    fn write_vtk(&mut self) {
        if let Some(dir) = &self.vtk_dir {
            let f = dir.join(format!("particles_{:05}.vtk", self.vtk_count));
            // a failed snapshot does not stop the run; the summary still tells the result
            let _ = std::fs::create_dir_all(dir).and_then(|_| std::fs::write(&f, super::vtk::legacy(&self.dem.p)));
            self.vtk_count += 1;
        }
    }

    /// Fluid density (kg/m^3).
    pub fn fluid_density(&self) -> f64 {
        self.rho_f
    }
}
