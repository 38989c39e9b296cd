//! The Eulerian two-fluid column: its closures, grid operator, state and coefficients,
//! built from a scene; the getters. The equations are advanced by the files named after
//! them ([`super::momentum`], [`super::temperature`], [`super::volume_fraction`],
//! [`super::k_omega`]) and stepped by [`super::stepper`].

use saltus_core::scene::Scene;
use saltus_core::Error;
use saltus_core::{DragLaw, DriftForm, EffectiveViscosity, Fluctuation, Turbulence};

use super::config::{Config, Top};
use super::rheology::{Elastic, Rheology};
use super::state::{Previous, Saved, State, Stepping};
use super::workspace::{Coefficients, Scratch};
use crate::column::turbulence::{friction_velocity, EddyViscosity, KOmegaPhysics, KOmegaRun};
use crate::column::{ColumnOperator, Grid};
use crate::inputs::DragKernel;
use crate::measures::transport_scales::TransportScales;
use crate::run::{Breakdown, Place};

/// Volume fraction below which a cell counts as clear fluid for the particle momentum
/// and temperature equations: their inertia uses max(phi, PHI_FLOOR) so that the rows stay
/// well posed where there are no particles (u_p there is the velocity a particle would
/// take, T diffuses).
pub const PHI_FLOOR: f64 = 1e-8;

/// Physical constants of the run.
#[derive(Clone, Copy, Debug)]
pub(super) struct Constants {
    pub rho_f: f64,
    pub nu_f: f64,
    pub rho_p: f64,
    pub d: f64,
    /// g sin(alpha)
    pub gx: f64,
    /// imposed steady -dp/dx (Pa/m), to which the forcing adds
    pub grad: f64,
    /// (rho_p - rho_f) g cos(alpha)
    pub buoyant_weight: f64,
}

/// The closures of the run, resolved once.
pub(super) struct Models<'a> {
    pub drag: &'a dyn DragLaw,
    pub viscosity: &'a dyn EffectiveViscosity,
    pub turbulence: &'a dyn Turbulence,
    /// `None` when the scene has no active fluctuation closure: no drift velocity
    pub fluctuation: Option<&'a dyn Fluctuation>,
    pub rheology: Rheology<'a>,
}

/// What a run of the column reads and never changes: the scene, its settings, the
/// constants, the closures and the grid operator.
pub(super) struct Params<'a> {
    pub scene: &'a Scene,
    pub cfg: Config,
    pub c: Constants,
    pub m: Models<'a>,
    pub kernel: DragKernel<'a>,
    pub kinetic: bool,
    pub op: ColumnOperator,
    pub k_omega_physics: KOmegaPhysics,
    /// form of the drift flux of the fluctuation closure (gradient without one)
    pub drift_form: DriftForm,
    /// volume fraction above which the wall-normal slip enters the drag: 1e-6 without a
    /// fluctuation closure; with one, any positive phi, because a suspension profile spans
    /// many decades (a Rouse profile over a smooth wall falls below 1e-15) and its grains
    /// settle at the terminal velocity of the drag law, not at the Stokes velocity that a
    /// zero slip would give
    pub slip_phi: f64,
    /// the scales of qs*, Shields and the nominal Shields number of the summary and the
    /// time series
    pub scales: TransportScales,
}

/// What a step recomputes from the state or keeps only within itself: the copy a
/// rejected step restores, the coefficients of the current state, the scratch of the
/// solves and the stages' wall time.
pub(super) struct Workspace {
    /// the state a rejected step restores
    pub saved: Saved,
    /// coefficients of the current state (kept current after every accepted step)
    pub co: Coefficients,
    pub sc: Scratch,
    /// wall time of the stages of the steps ([`super::STAGES`])
    pub stages: crate::run::Stages,
}

/// The Eulerian two-fluid column of Chassagne et al. 2023 section 2.1; see the module
/// documentation of [`crate::eulerian`] for the equations and the discretisation.
pub struct Eulerian<'a> {
    pub(super) params: Params<'a>,
    /// the solution and the stepping between accepted steps
    pub(super) state: State,
    pub(super) work: Workspace,
}

impl<'a> Eulerian<'a> {
    /// Build the column of `scene` with its `[domain]` and `[solver]` read into `cfg`.
    pub fn new(scene: &'a Scene, cfg: Config) -> Result<Self, Error> {
        let file = scene.path.display();
        let cl = &scene.closures;
        let missing = |family: &str| Error::Invalid(format!("{file}: closures.{family} is not resolved"));
        let granular = cl.granular.as_deref().ok_or_else(|| Error::Key {
            file: scene.path.clone(),
            key: "closures.granular".into(),
            message: "missing; the Eulerian solver needs a granular closure (mu_i, mu_k or frictional_collisional)"
                .into(),
        })?;
        let rheology = if let Some(k) = granular.as_kinetic() {
            Rheology::Kinetic { model: k, elastic: k.elastic_law() }
        } else if let Some(l) = granular.as_local() {
            // elastic_phi_rlp < phi_max is checked when the scene is loaded
            let phi_max = l.packing(0.0);
            Rheology::Local {
                model: l,
                elastic: Elastic {
                    p0: cfg.settings.elastic_p0,
                    phi_rlp: cfg
                        .settings
                        .elastic_phi_rlp
                        .unwrap_or_else(|| saltus_core::scene::default_elastic_phi_rlp(phi_max)),
                    phi_max,
                },
            }
        } else {
            return Err(Error::Invalid(format!(
                "{file}: closures.granular `{}` is neither a local rheology nor a kinetic theory",
                granular.name()
            )));
        };
        let turbulence = cl.turbulence.as_deref().ok_or_else(|| missing("turbulence"))?;
        let two_equation = turbulence.as_two_equation();
        if !turbulence.transported().is_empty() && two_equation.is_none() {
            return Err(Error::Invalid(format!(
                "{file}: closures.turbulence `{}` transports fields {:?}, of which the Eulerian solver advances only k and omega of a two-equation closure (k_omega)",
                turbulence.name(),
                turbulence.transported()
            )));
        }
        if two_equation.is_some() && scene.domain.top == Top::Lid {
            return Err(Error::Key {
                file: scene.path.clone(),
                key: "domain.top".into(),
                message: format!(
                    "`lid` is not supported with closures.turbulence `{}` (no wall treatment at a moving lid); use `free_surface` or `symmetry`",
                    turbulence.name()
                ),
            });
        }
        let fluctuation = cl.fluctuation.as_deref().filter(|f| f.is_active());
        let drag = cl.drag.as_deref().ok_or_else(|| missing("drag"))?;
        let hindrance = cl.hindrance.as_deref().ok_or_else(|| missing("hindrance"))?;
        let m = Models {
            drag,
            viscosity: cl.viscosity.as_deref().ok_or_else(|| missing("viscosity"))?,
            turbulence,
            fluctuation,
            rheology,
        };
        let slope = scene.physics.slope;
        let g = scene.physics.gravity;
        let cos = (1.0 - slope * slope).max(0.0).sqrt();
        let c = Constants {
            rho_f: scene.fluid.density,
            nu_f: scene.fluid.viscosity,
            rho_p: scene.particles.density,
            d: scene.particles.diameter,
            gx: g * slope,
            grad: scene.physics.pressure_gradient,
            buoyant_weight: (scene.particles.density - scene.fluid.density) * g * cos,
        };
        let d = &scene.domain;
        let n = cfg.cells;
        let height = d.bed_height + d.water_depth;
        // uniform, or geometric from the wall (domain.stretching, checked by Config)
        let grid = Grid::geometric(n, height, d.stretching).map_err(|e| Error::OutOfRange {
            file: scene.path.clone(),
            key: "domain.stretching".into(),
            value: d.stretching.to_string(),
            allowed: format!("a grid of domain.cells over the column: {e}"),
        })?;
        let op = ColumnOperator::new(grid);
        let (zf, dz) = (op.grid().faces(), op.grid().dz());
        // the scene resolved the packing of the bed (domain.bed_phi, below the closure's
        // maximum packing) when it was loaded
        let bed_phi = d.bed_phi.unwrap_or(saltus_core::scene::EULERIAN_BED_PHI);
        // initial bed: cells fully inside get bed_phi, the cell cut by the bed top a share,
        // so that the sediment mass is exactly bed_phi * bed_height
        let phi: Vec<f64> = (0..n)
            .map(|i| {
                let inside = ((d.bed_height - zf[i]) / dz[i]).clamp(0.0, 1.0);
                inside * bed_phi + (1.0 - inside) * d.suspension_phi
            })
            .collect();
        let kinetic = matches!(m.rheology, Rheology::Kinetic { .. });
        let t0 = if kinetic { cfg.settings.initial_temperature } else { 0.0 };
        let mass0 = phi.iter().zip(dz).map(|(p, h)| p * h).sum();
        // the fluid above the initial bed carries the driving (at least the top cell)
        let u_star = friction_velocity(c.grad / c.rho_f + c.gx, d.water_depth.max(dz[n - 1]));
        let kw = two_equation.map(|model| KOmegaRun::new(model, &phi, u_star, height, c.nu_f, c.d));
        let k_omega_physics = KOmegaPhysics {
            nu_f: c.nu_f,
            diameter: c.d,
            fluid_density: c.rho_f,
            particle_density: c.rho_p,
            gravity_normal: g * cos,
            friction_velocity: u_star,
        };
        let stepping =
            Stepping { dt: cfg.settings.dt_initial.min(cfg.settings.dt_max), calm: 0, previous: Previous::default() };
        let state = State {
            stepping,
            time: 0.0,
            steps: 0,
            rejected: 0,
            residual: f64::INFINITY,
            phi,
            uf: vec![0.0; n],
            up: vec![0.0; n],
            temp: vec![t0; n],
            flux: vec![0.0; n + 1],
            drift_flux: vec![0.0; n + 1],
            eddy: EddyViscosity::new(n, cfg.settings.eddy_relaxation),
            kw,
            mass0,
        };
        let params = Params {
            scene,
            kernel: DragKernel::new(drag, hindrance),
            c,
            m,
            kinetic,
            op,
            k_omega_physics,
            drift_form: fluctuation.map_or(DriftForm::Gradient, |f| f.drift_form()),
            slip_phi: if fluctuation.is_some() { f64::MIN_POSITIVE } else { 1e-6 },
            scales: TransportScales::new(
                scene,
                scene.particles.density,
                scene.particles.diameter,
                scene.domain.water_depth,
            ),
            cfg,
        };
        let work = Workspace {
            saved: Saved::default(),
            stages: crate::run::Stages::new(&super::STAGES),
            co: Coefficients::new(n),
            sc: Scratch::new(n),
        };
        let mut model = Self { params, state, work };
        model.evaluate().map_err(|b| Error::Invalid(format!("{file}: initial state: {b}")))?;
        Ok(model)
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.state.len()
    }
    /// Always false: a column has at least 4 cells.
    pub fn is_empty(&self) -> bool {
        self.state.phi.is_empty()
    }
    /// The grid operator.
    pub fn operator(&self) -> &ColumnOperator {
        &self.params.op
    }
    /// Cell centres (m).
    pub fn z(&self) -> &[f64] {
        self.params.op.grid().centres()
    }
    /// Cell height (m).
    pub fn dz(&self) -> &[f64] {
        self.params.op.grid().dz()
    }
    /// Faces (m).
    pub fn faces(&self) -> &[f64] {
        self.params.op.grid().faces()
    }
    /// Solid volume fraction per cell.
    pub fn phi(&self) -> &[f64] {
        &self.state.phi
    }
    /// Fluid streamwise velocity per cell (m/s).
    pub fn u_f(&self) -> &[f64] {
        &self.state.uf
    }
    /// Particle streamwise velocity per cell (m/s).
    pub fn u_p(&self) -> &[f64] {
        &self.state.up
    }
    /// Granular temperature per cell (m^2/s^2); zeros without kinetic theory.
    pub fn temperature(&self) -> &[f64] {
        &self.state.temp
    }
    /// Whether the granular temperature equation is solved.
    pub fn is_kinetic(&self) -> bool {
        self.params.kinetic
    }
    /// Particle volume flux phi w_p through the faces (m/s).
    pub fn flux(&self) -> &[f64] {
        &self.state.flux
    }
    /// Eddy viscosity per cell (m^2/s), as relaxed for the current coefficients.
    pub fn eddy_viscosity(&self) -> &[f64] {
        self.state.eddy.values()
    }
    /// Turbulent kinetic energy and specific dissipation rate per cell, when the
    /// turbulence closure transports them.
    pub fn k_omega(&self) -> Option<(&[f64], &[f64])> {
        self.state.kw.as_ref().map(|kw| (kw.col.k.as_slice(), kw.col.omega.as_slice()))
    }
    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.state.time
    }
    /// Accepted steps.
    pub fn steps(&self) -> usize {
        self.state.steps
    }
    /// Rejected steps.
    pub fn rejected_steps(&self) -> usize {
        self.state.rejected
    }
    /// Last steady residual (1/s).
    pub fn residual(&self) -> f64 {
        self.state.residual
    }
    /// Settings in use.
    pub fn config(&self) -> &Config {
        &self.params.cfg
    }
    /// Sediment mass per unit bed area over rho_p: sum phi dz (m).
    pub fn sediment_height(&self) -> f64 {
        self.state.sediment_height(self.dz())
    }
    /// |mass - initial mass| / initial mass (0 for clear fluid).
    pub fn mass_error(&self) -> f64 {
        if self.state.mass0 > 0.0 {
            (self.sediment_height() - self.state.mass0).abs() / self.state.mass0
        } else {
            0.0
        }
    }
    /// Set the velocities (tests and restarts); the coefficients follow.
    pub fn set_velocities(&mut self, uf: &[f64], up: &[f64]) -> Result<(), Breakdown> {
        self.state.uf.copy_from_slice(uf);
        self.state.up.copy_from_slice(up);
        self.evaluate()
    }

    /// Particle pressure per cell (Pa) at the current state (elastic, kinetic or
    /// dilatancy; without the overburden of a blocked surface face).
    pub fn particle_pressure(&self) -> Vec<f64> {
        self.work.co.pres.iter().map(|p| p.p).collect()
    }
}

/// The breakdown of `field` at `cell` (the column when the index is past its cells) at
/// the state's time.
pub(super) fn breakdown(
    params: &Params,
    state: &State,
    cell: usize,
    field: &'static str,
    value: f64,
    reason: String,
) -> Breakdown {
    let place = match params.op.grid().centres().get(cell) {
        Some(&z) => Place::Cell { index: cell, z },
        None => Place::Column,
    };
    Breakdown { time: state.time, place, field: field.into(), value, reason }
}

impl Params<'_> {
    /// Top value of the fluid velocity in the shear rate: the lid's, or that of a
    /// stress-free top ([`crate::column::ColumnOperator::stress_free_shear_top`]).
    pub(super) fn fluid_top(&self, u: &[f64]) -> f64 {
        match self.scene.domain.top {
            Top::Lid => self.scene.domain.lid_velocity,
            _ => self.op.stress_free_shear_top(u),
        }
    }
}
