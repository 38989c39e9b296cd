//! The coupled run: deposition, then DEM steps with the fluid column solved every fluid
//! period (Maurin et al. 2015 section II D). This file builds it from the scene; the
//! stepping is in `stepping.rs`, the deposition in `deposition.rs`.

use saltus_core::scene::{PhiAverage, Scene};
use saltus_core::Error;

use super::config::{Config, FluidMode, Initial};
use super::params::Params;
use super::setup::{self, Material};
use super::state::{Stage, State};
use super::workspace::Workspace;
use crate::column::{FluidColumn, Grid, TopBoundary};
use crate::lagrangian::coupling::averaging::CellSums;
use crate::lagrangian::coupling::damping::SlipAverage;
use crate::lagrangian::coupling::drag::{FluidField, FluidForces};
use crate::lagrangian::coupling::smoothing::PhiWindow;
use crate::lagrangian::engine::contact::{ContactLaw, ContactModel};
use crate::lagrangian::engine::dem::Dem;
use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::stats::granular::GranularStats;
use crate::lagrangian::stats::statistics::Stats;
use crate::lagrangian::stats::steady::Steady;
use crate::measures::transport_scales::TransportScales;
use saltus_core::grain::{carnahan_starling, sphere_volume};

pub use crate::lagrangian::coupling::exchange::MAX_SPEED;

/// Overlap of a contact over the smaller diameter beyond which the run is declared
/// unstable: grains passing through each other. The rigid-limit stiffness keeps overlaps
/// near 4e-4 d under the weight of the bed, and collisions at the default time step stay
/// within a few per cent of d; past a quarter of a diameter a soft-sphere contact models
/// nothing (and the packing of the slices heads for values above 1).
pub const MAX_OVERLAP: f64 = 0.25;

/// Most DEM steps a scene may ask for (deposition and flow): the top of the range of
/// `solver.lagrangian.max_steps`.
pub const MAX_DEM_STEPS: f64 = 1e15;

/// DEM steps between two checks of the state (and two returns to the driver) when the
/// fluid period is longer: the state is checked at every fluid update and at least this
/// often.
pub const CHECK_STEPS: u64 = 2000;

/// The Lagrangian solver of a scene: what the scene resolved to ([`Params`], read-only),
/// the state a checkpoint carries ([`State`]) and the scratch every step refills
/// ([`Workspace`]). The driver advances it through [`crate::run::Stepper`]; tests and
/// benches read it through its getters.
pub struct Lagrangian<'a> {
    pub(crate) params: Params<'a>,
    pub(crate) state: State,
    pub(crate) work: Workspace,
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
        .with_normal_force(s.normal_force)
        .with_tangential_history(s.tangential_history);
        let m = rho_p * sphere_volume(d);
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
        // the drag damping of a two-equation closure from the time-averaged relative velocity
        // of the phases (Cheng eq 24), when the closure asks for it
        let slip_average = s.numerics.fluid == FluidMode::Coupled
            && turbulence.as_two_equation().and_then(|m| m.slip_average_start()).is_some();
        let column = if s.numerics.fluid == FluidMode::Coupled {
            let params = crate::column::ColumnParams {
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
        let pool = super::workspace::pool(s.numerics.threads, &scene.path)?;
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
        let granular = s.numerics.granular_fields.unwrap_or(s.numerics.fluid != FluidMode::Off);
        Ok(Self {
            params: Params {
                scene,
                viscosity,
                turbulence,
                drag,
                hindrance,
                fluctuation,
                re_free_hindrance: re_free,
                fluid_every,
                settle_total,
                flow_body,
                scales: TransportScales::new(scene, mat.rho_p, mat.d, cfg.domain.water_depth),
                mat,
                seed: scene.seed,
                column_params,
                haff,
                cfg: cfg.clone(),
            },
            state: State {
                stage: if deposit { Stage::Deposition } else { Stage::Flow },
                time: 0.0,
                steps: 0,
                settle_steps: 0,
                dem,
                forces,
                field,
                column,
                sums: CellSums::new(cells),
                phi: v(0.0),
                u_p: v(0.0),
                beta: v(0.0),
                tau_t: v(0.0),
                stats: Stats::new(cells),
                granular: granular.then(|| GranularStats::new(cells)),
                steady: Steady::new(s.numerics.steady_window, s.numerics.steady_tolerance, s.numerics.steady_windows),
                truncation: Default::default(),
                cell_volume: cfg.domain.length * cfg.domain.width * dz,
                bed_surface: cfg.bed_surface(),
                slip: SlipAverage::new(if slip_average { cells } else { 0 }),
                start: None,
                phi_window: PhiWindow::new(if s.numerics.phi_average == PhiAverage::FluidPeriod { cells } else { 0 }),
            },
            work: Workspace::new(n, cells, pool),
        })
    }
}

/// sqrt(pi) d / (4 (1 - e^2) phi g0), Carnahan-Starling g0, for the scenes whose
/// temperature Haff's law describes (see [`crate::lagrangian::stats::cooling::Cooling`]): an inelastic,
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
    let phi = p.n_mobile as f64 * sphere_volume(d) / volume;
    let g0 = carnahan_starling(phi);
    let e = s.restitution;
    crate::output::finite(std::f64::consts::PI.sqrt() * d / (4.0 * (1.0 - e * e) * phi * g0)).filter(|h| *h > 0.0)
}
