//! The Eulerian two-fluid column: state, one time step, adaptive stepping to steady state.

use saltus_core::scene::Scene;
use saltus_core::{ColumnView, Error};
use saltus_core::{
    DragLaw, EffectiveViscosity, FlowScales, Fluctuation, Hindrance, KineticCoefficients, LocalState, SaltationInput,
    Turbulence, TurbulencePoint,
};

use super::block::BlockTridiagonal;
use super::config::{Config, Top};
use super::rheology::{coulomb, Elastic, Rheology};
use crate::column::k_omega::{ColumnGeometry, KOmegaColumn};
use crate::column::Tridiagonal;
use saltus_core::closure::turbulence::{TwoEquation, TwoEquationInput};

/// Volume fraction below which a cell counts as clear fluid for the particle momentum
/// and temperature equations: their inertia uses max(phi, PHI_FLOOR) so that the rows stay
/// well posed where there are no particles (u_p there is the velocity a particle would
/// take, T diffuses).
pub const PHI_FLOOR: f64 = 1e-8;

/// Where and why a run stopped: time, cell, field.
#[derive(Clone, Debug, PartialEq)]
pub struct Breakdown {
    /// simulated time (s)
    pub time: f64,
    /// cell index from the bottom
    pub cell: usize,
    /// cell centre (m)
    pub z: f64,
    /// field that went bad
    pub field: &'static str,
    /// its value
    pub value: f64,
    /// what is wrong
    pub reason: String,
}

impl std::fmt::Display for Breakdown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {:.6} s: {} = {:e} in cell {} (z = {:.6} m): {}",
            self.time, self.field, self.value, self.cell, self.z, self.reason
        )
    }
}

/// Physical constants of the run.
#[derive(Clone, Copy, Debug)]
struct Constants {
    rho_f: f64,
    nu_f: f64,
    rho_p: f64,
    d: f64,
    /// g sin(alpha)
    gx: f64,
    /// imposed -dp/dx (Pa/m)
    grad: f64,
    /// (rho_p - rho_f) g cos(alpha)
    buoyant_weight: f64,
}

/// The closures of the run, resolved once.
struct Models<'a> {
    drag: &'a dyn DragLaw,
    hindrance: &'a dyn Hindrance,
    viscosity: &'a dyn EffectiveViscosity,
    turbulence: &'a dyn Turbulence,
    /// `None` when the scene has no active fluctuation closure: no drift velocity
    fluctuation: Option<&'a dyn Fluctuation>,
    rheology: Rheology<'a>,
}

/// Outcome of one attempted step.
enum Attempt {
    Accepted,
    /// rejected, state restored; the step is retried with a smaller dt
    Rejected(Breakdown),
}

/// Progress report handed to the observer of [`Eulerian::run`].
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    /// simulated time (s)
    pub time: f64,
    /// end time (s)
    pub end_time: f64,
    /// accepted steps
    pub steps: usize,
    /// current time step (s)
    pub dt: f64,
    /// steady residual (1/s)
    pub residual: f64,
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    /// steady residual below tolerance
    Steady,
    /// end time reached
    EndTime,
    /// step cap reached
    MaxSteps,
    /// the time step fell below dt_min: the last rejection says where and why
    Unstable(Breakdown),
}

/// The Eulerian two-fluid column of Chassagne et al. 2023 section 2.1; see the module
/// documentation of [`crate::eulerian`] for the equations and the discretisation.
pub struct Eulerian<'a> {
    cfg: Config,
    c: Constants,
    m: Models<'a>,
    kinetic: bool,
    // grid
    zc: Vec<f64>,
    zf: Vec<f64>,
    dz: Vec<f64>,
    /// centre distance across each face (interior faces 1..n)
    h: Vec<f64>,
    wall: [f64; 2],
    top_wall: [f64; 3],
    // state
    time: f64,
    steps: usize,
    rejected: usize,
    phi: Vec<f64>,
    uf: Vec<f64>,
    up: Vec<f64>,
    temp: Vec<f64>,
    /// particle volume flux phi w_p through each face (m/s), faces 0..=n
    flux: Vec<f64>,
    nu_t: Vec<f64>,
    mass0: f64,
    residual: f64,
    // saved state for rejection
    saved: [Vec<f64>; 5],
    /// face coefficients (c_L, c_R, s) of the volume-fraction fluxes, reused every step
    face_coeffs: Vec<f64>,
    // coefficients
    gamma_f: Vec<f64>,
    gamma_p: Vec<f64>,
    face_gamma: Vec<f64>,
    work: Vec<f64>,
    k_drag: Vec<f64>,
    beta: Vec<f64>,
    drag_tangent: Vec<f64>,
    cd_ratio: Vec<f64>,
    mobility: Vec<f64>,
    pres: Vec<super::rheology::Pressure>,
    /// local rheologies: weight of the grains above a face whose flux is blocked (the free
    /// surface of a dense layer), added to the pressure of the cells below it (Pa)
    overburden: Vec<f64>,
    visc_ratio: Vec<f64>,
    drift: Vec<f64>,
    coef: Vec<KineticCoefficients>,
    f1_slope: Vec<f64>,
    eta_kin: Vec<f64>,
    kappa: Vec<f64>,
    /// particle stress at faces: tau = eta_face g + sigma_face
    eta_face: Vec<f64>,
    sigma_face: Vec<f64>,
    tau_p: Vec<f64>,
    fluid_cond: Vec<f64>,
    fluid_k: Vec<f64>,
    block: BlockTridiagonal,
    xb: Vec<[f64; 2]>,
    tri: Tridiagonal,
    /// k-omega state, present only when the turbulence closure transports k and omega
    kw: Option<TwoEquationRun<'a>>,
}

/// The k and omega of a two-equation turbulence closure with the per-cell inputs its
/// terms need, allocated only when the scene selects such a closure.
struct TwoEquationRun<'a> {
    model: &'a dyn TwoEquation,
    col: KOmegaColumn,
    /// friction velocity of the forcing at the bed surface (m/s)
    u_star: f64,
    /// g cos(alpha)
    gravity_normal: f64,
    shear: Vec<f64>,
    dphidz: Vec<f64>,
    drag: Vec<f64>,
}

/// minmod limiter: the smaller slope when both have the same sign, else 0.
#[inline]
fn minmod(a: f64, b: f64) -> f64 {
    if a * b <= 0.0 {
        0.0
    } else if a.abs() < b.abs() {
        a
    } else {
        b
    }
}

/// Value of the cell field `u` at interior face `j`, linear between the two centres (the
/// mean of the two on a uniform grid).
#[inline]
fn face_value(zc: &[f64], zf: &[f64], u: &[f64], j: usize) -> f64 {
    let t = (zf[j] - zc[j - 1]) / (zc[j] - zc[j - 1]);
    u[j - 1] + t * (u[j] - u[j - 1])
}

fn wall_stencil(a: f64, b: f64) -> [f64; 3] {
    // du/ds at the wall from u_w, u(a), u(b), exact for quadratics: [c_w, c_a, c_b]
    [-(a + b) / (a * b), b / (a * (b - a)), -a / (b * (b - a))]
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
            Rheology::Kinetic(k)
        } else if let Some(l) = granular.as_local() {
            let phi_max = l.packing(0.0);
            if cfg.settings.elastic_phi_rlp >= phi_max {
                return Err(Error::OutOfRange {
                    file: scene.path.clone(),
                    key: "solver.elastic_phi_rlp".into(),
                    value: cfg.settings.elastic_phi_rlp.to_string(),
                    allowed: format!("< {phi_max} (the closure's packing at zero shear)"),
                });
            }
            Rheology::Local {
                model: l,
                elastic: Elastic { p0: cfg.settings.elastic_p0, phi_rlp: cfg.settings.elastic_phi_rlp, phi_max },
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
        if two_equation.is_some() && cfg.domain.top == Top::Lid {
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
        let m = Models {
            drag: cl.drag.as_deref().ok_or_else(|| missing("drag"))?,
            hindrance: cl.hindrance.as_deref().ok_or_else(|| missing("hindrance"))?,
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
        let d = &cfg.domain;
        let n = d.cells;
        let height = d.bed_height + d.water_depth;
        // uniform, or geometric from the wall (domain.stretching, checked by Config)
        let grid = crate::column::Grid::geometric(n, height, d.stretching).map_err(|e| Error::OutOfRange {
            file: scene.path.clone(),
            key: "domain.stretching".into(),
            value: d.stretching.to_string(),
            allowed: format!("a grid of domain.cells over the column: {e}"),
        })?;
        let zf = grid.faces().to_vec();
        let zc = grid.centres().to_vec();
        let dz = grid.dz().to_vec();
        // distances between neighbouring centres (the wall and the top: half cells)
        let mut h = vec![0.0; n + 1];
        h[0] = zc[0];
        h[n] = zf[n] - zc[n - 1];
        for j in 1..n {
            h[j] = zc[j] - zc[j - 1];
        }
        let phi_max = m.rheology.phi_max();
        let bed_phi = d.bed_phi.unwrap_or(if 0.61 < 0.95 * phi_max { 0.61 } else { 0.95 * phi_max });
        if bed_phi >= phi_max || d.suspension_phi >= phi_max {
            return Err(Error::OutOfRange {
                file: scene.path.clone(),
                key: if bed_phi >= phi_max { "domain.bed_phi" } else { "domain.suspension_phi" }.into(),
                value: bed_phi.max(d.suspension_phi).to_string(),
                allowed: format!("< {phi_max} (maximum packing of closures.granular)"),
            });
        }
        // initial bed: cells fully inside get bed_phi, the cell cut by the bed top a share,
        // so that the sediment mass is exactly bed_phi * bed_height
        let phi: Vec<f64> = (0..n)
            .map(|i| {
                let inside = ((d.bed_height - zf[i]) / dz[i]).clamp(0.0, 1.0);
                inside * bed_phi + (1.0 - inside) * d.suspension_phi
            })
            .collect();
        let kinetic = matches!(m.rheology, Rheology::Kinetic(_));
        let t0 = if kinetic { cfg.settings.initial_temperature } else { 0.0 };
        let mass0 = phi.iter().zip(&dz).map(|(p, h)| p * h).sum();
        let (a, b) = (zc[0], zc[1]);
        let wall = {
            let s = wall_stencil(a, b);
            [s[1], s[2]]
        };
        let top_wall = wall_stencil(zf[n] - zc[n - 1], zf[n] - zc[n - 2]);
        let v = |x: f64| vec![x; n];
        let kw = two_equation.map(|model| {
            // friction velocity of the driving over the water depth: the fluid shear stress
            // at the bed surface of a clear-water column
            let drive = c.grad / c.rho_f + c.gx;
            let u_star = (drive.max(0.0) * d.water_depth.max(dz[n - 1])).sqrt();
            let (k0, w0) = model.initial_state(u_star, height, c.nu_f);
            TwoEquationRun {
                model,
                col: KOmegaColumn::new(n, k0, w0),
                u_star,
                gravity_normal: g * cos,
                shear: v(0.0),
                dphidz: v(0.0),
                drag: v(0.0),
            }
        });
        Ok(Self {
            kw,
            c,
            m,
            kinetic,
            wall,
            top_wall,
            time: 0.0,
            steps: 0,
            rejected: 0,
            phi,
            uf: v(0.0),
            up: v(0.0),
            temp: v(t0),
            flux: vec![0.0; n + 1],
            nu_t: v(0.0),
            mass0,
            residual: f64::INFINITY,
            saved: Default::default(),
            face_coeffs: Vec::with_capacity(3 * (n + 1)),
            gamma_f: v(0.0),
            gamma_p: v(0.0),
            face_gamma: vec![0.0; n + 1],
            work: v(0.0),
            k_drag: v(0.0),
            beta: v(0.0),
            drag_tangent: v(1.0),
            cd_ratio: v(0.0),
            mobility: v(0.0),
            pres: vec![Default::default(); n],
            overburden: v(0.0),
            visc_ratio: v(1.0),
            drift: v(0.0),
            coef: vec![Default::default(); n],
            f1_slope: v(0.0),
            eta_kin: v(0.0),
            kappa: v(0.0),
            eta_face: vec![0.0; n + 1],
            sigma_face: vec![0.0; n + 1],
            tau_p: vec![0.0; n + 1],
            fluid_cond: vec![0.0; n + 1],
            fluid_k: v(0.0),
            block: BlockTridiagonal::new(n),
            xb: vec![[0.0; 2]; n],
            tri: Tridiagonal::new(n),
            zc,
            zf,
            dz,
            h,
            cfg,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.phi.len()
    }
    /// Always false: a column has at least 4 cells.
    pub fn is_empty(&self) -> bool {
        self.phi.is_empty()
    }
    /// Cell centres (m).
    pub fn z(&self) -> &[f64] {
        &self.zc
    }
    /// Cell height (m).
    pub fn dz(&self) -> &[f64] {
        &self.dz
    }
    /// Faces (m).
    pub fn faces(&self) -> &[f64] {
        &self.zf
    }
    /// Solid volume fraction per cell.
    pub fn phi(&self) -> &[f64] {
        &self.phi
    }
    /// Fluid streamwise velocity per cell (m/s).
    pub fn u_f(&self) -> &[f64] {
        &self.uf
    }
    /// Particle streamwise velocity per cell (m/s).
    pub fn u_p(&self) -> &[f64] {
        &self.up
    }
    /// Granular temperature per cell (m^2/s^2); zeros without kinetic theory.
    pub fn temperature(&self) -> &[f64] {
        &self.temp
    }
    /// Whether the granular temperature equation is solved.
    pub fn is_kinetic(&self) -> bool {
        self.kinetic
    }
    /// Particle volume flux phi w_p through the faces (m/s).
    pub fn flux(&self) -> &[f64] {
        &self.flux
    }
    /// Eddy viscosity per cell (m^2/s).
    pub fn eddy_viscosity(&self) -> &[f64] {
        &self.nu_t
    }
    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }
    /// Accepted steps.
    pub fn steps(&self) -> usize {
        self.steps
    }
    /// Rejected steps.
    pub fn rejected_steps(&self) -> usize {
        self.rejected
    }
    /// Last steady residual (1/s).
    pub fn residual(&self) -> f64 {
        self.residual
    }
    /// Settings in use.
    pub fn config(&self) -> &Config {
        &self.cfg
    }
    /// Sediment mass per unit bed area over rho_p: sum phi dz (m).
    pub fn sediment_height(&self) -> f64 {
        self.phi.iter().zip(&self.dz).map(|(p, h)| p * h).sum()
    }
    /// |mass - initial mass| / initial mass (0 for clear fluid).
    pub fn mass_error(&self) -> f64 {
        if self.mass0 > 0.0 {
            (self.sediment_height() - self.mass0).abs() / self.mass0
        } else {
            0.0
        }
    }
    /// Set the velocities (tests and restarts).
    pub fn set_velocities(&mut self, uf: &[f64], up: &[f64]) {
        self.uf.copy_from_slice(uf);
        self.up.copy_from_slice(up);
    }

    /// Particle pressure per cell (Pa) at the current state.
    pub fn particle_pressure(&mut self) -> Vec<f64> {
        self.evaluate();
        self.pres.iter().map(|p| p.p).collect()
    }

    /// Profiles of derived fields at the current state, cell-centred: particle shear stress,
    /// fluid shear stress (viscous + turbulent), particle pressure, particle wall-normal
    /// velocity, the control number of a local rheology (I or K) or 0.
    pub fn derived(&mut self) -> Derived {
        self.evaluate();
        let n = self.len();
        let mut out = Derived::default();
        for i in 0..n {
            let eps = 1.0 - self.phi[i].max(0.0);
            out.tau_p.push(0.5 * (self.tau_p[i] + self.tau_p[i + 1]));
            out.tau_f.push(self.c.rho_f * eps * (self.c.nu_f * self.visc_ratio[i] + self.nu_t[i]) * self.gamma_f[i]);
            out.p_p.push(self.pres[i].p + self.overburden[i]);
            let f = 0.5 * (self.flux[i] + self.flux[i + 1]);
            out.w_p.push(if self.phi[i] > 1e-6 { f / self.phi[i] } else { 0.0 });
            out.control.push(match self.m.rheology {
                Rheology::Local { model, .. } => {
                    model.control_number(&self.local_state(self.gamma_p[i], self.pres[i].p + self.overburden[i]))
                }
                Rheology::Kinetic(_) => {
                    let s = self.local_state(self.gamma_p[i], self.pres[i].p);
                    s.inertial_number()
                }
            });
        }
        out
    }

    fn local_state(&self, gamma: f64, p: f64) -> LocalState {
        LocalState {
            shear_rate: gamma,
            pressure: p,
            diameter: self.c.d,
            particle_density: self.c.rho_p,
            fluid_viscosity: self.c.rho_f * self.c.nu_f,
        }
    }

    /// Shear rates at cells (from face values) and at faces, for u_f and u_p.
    fn shear_rates(&mut self) {
        let n = self.len();
        let lid = match self.cfg.domain.top {
            Top::Lid => Some(self.cfg.domain.lid_velocity),
            _ => None,
        };
        for (u, g, top) in [(&self.uf, &mut self.gamma_f, lid), (&self.up, &mut self.gamma_p, None)] {
            let mut below = 0.0;
            for (i, (g, &dz)) in g.iter_mut().zip(&self.dz).enumerate() {
                let above = if i + 1 < n { face_value(&self.zc, &self.zf, u, i + 1) } else { top.unwrap_or(u[n - 1]) };
                *g = (above - below) / dz;
                below = above;
            }
        }
        let up = &self.up;
        self.face_gamma[0] = self.wall[0] * up[0] + self.wall[1] * up[1];
        for j in 1..n {
            self.face_gamma[j] = (up[j] - up[j - 1]) / self.h[j];
        }
        self.face_gamma[n] = 0.0;
    }

    /// Every coefficient of the step from the current state.
    fn evaluate(&mut self) {
        self.shear_rates();
        let n = self.len();
        let c = self.c;
        let s = &self.cfg.settings;
        // drag: K with the full slip magnitude (streamwise and wall-normal)
        let stokes = 0.75 * c.rho_f * c.nu_f / (c.d * c.d);
        let cd_inf = self.m.drag.cd_inf();
        for i in 0..n {
            let phi = self.phi[i].clamp(0.0, 1.0 - 1e-12);
            let eps = 1.0 - phi;
            let f = 0.5 * (self.flux[i] + self.flux[i + 1]);
            let wp = if phi > 1e-6 { f / phi } else { 0.0 };
            let slip = (self.uf[i] - self.up[i]).hypot(wp / eps);
            let re = slip * c.d / c.nu_f;
            let re_h = self.m.hindrance.drag_reynolds(phi, re);
            // C_D(Re_h) |u_r| = cd_re(Re_h) nu / d * (Re / Re_h); Re/Re_h is the linear
            // convention factor, finite as Re -> 0
            let conv = 1.0 / self.m.hindrance.drag_reynolds(phi, 1.0);
            let cdre = self.m.drag.cd_re(re_h);
            let fh = self.m.hindrance.factor(phi, re);
            // C = phi eps K / phi (kg m^-3 s^-1): beta = phi C, K = C / eps
            let cc = stokes * fh * cdre * conv;
            // d ln C / d ln Re for the Newton linearisation of the streamwise drag: a Picard
            // lag of a quadratic drag (slip <- F / (c slip)) oscillates without damping
            let slope = if re > 1e-12 {
                let re2 = re * 1.000001;
                let c2 =
                    self.m.hindrance.factor(phi, re2) * self.m.drag.cd_re(self.m.hindrance.drag_reynolds(phi, re2));
                ((c2 / (fh * cdre)).ln() / 1.000001f64.ln()).max(0.0)
            } else {
                0.0
            };
            let ux = self.uf[i] - self.up[i];
            self.drag_tangent[i] = 1.0 + if slip > 0.0 { slope * ux * ux / (slip * slip) } else { 0.0 };
            self.beta[i] = phi * cc;
            self.k_drag[i] = cc / eps;
            self.mobility[i] = eps * eps / cc;
            self.cd_ratio[i] = if cdre > 0.0 { cd_inf * re_h / cdre } else { 0.0 };
        }
        // fluid viscosity and eddy viscosity (under-relaxed Picard between steps)
        self.m.viscosity.ratio_batch(&self.phi, &mut self.visc_ratio);
        let kw_fields = self.kw.as_ref().map(|kw| kw.col.fields());
        let transported: &[&[f64]] = kw_fields.as_ref().map_or(&[], |f| f.as_slice());
        let col = ColumnView {
            z: &self.zc,
            dz: &self.dz,
            phi: &self.phi,
            dudz: &self.gamma_f,
            diameter: c.d,
            nu_f: c.nu_f,
            transported,
        };
        self.m.turbulence.eddy_viscosity(&col, &mut self.work);
        let w = if self.steps == 0 { 1.0 } else { s.eddy_relaxation };
        for (nt, &new) in self.nu_t.iter_mut().zip(&self.work) {
            *nt = w * new + (1.0 - w) * *nt;
        }
        for i in 0..n {
            let eps = 1.0 - self.phi[i].max(0.0);
            self.fluid_k[i] = eps * (c.nu_f * self.visc_ratio[i] + self.nu_t[i]);
        }
        for j in 1..n {
            let resistance =
                (self.zf[j] - self.zc[j - 1]) / self.fluid_k[j - 1] + (self.zc[j] - self.zf[j]) / self.fluid_k[j];
            self.fluid_cond[j] = c.rho_f / resistance;
        }
        // drift diffusivity of the fluctuation closure (Chassagne eqs 4.3-4.4)
        if let Some(fl) = self.m.fluctuation {
            let depth = self.zf[n];
            let bulk = self.uf.iter().zip(&self.dz).map(|(u, h)| u * h).sum::<f64>() / depth;
            let scales = FlowScales { depth, bulk_velocity: bulk };
            for i in 0..n {
                let (k, omega) = self.kw.as_ref().map_or((0.0, 0.0), |kw| (kw.col.k[i], kw.col.omega[i]));
                let tp = TurbulencePoint {
                    k,
                    omega,
                    nu_t: self.nu_t[i],
                    reynolds_stress: self.nu_t[i] * self.gamma_f[i].abs(),
                };
                self.drift[i] = fl.diffusivity(&tp, &scales).max(0.0);
            }
        }
        // particle pressure and stress
        let r = s.shear_rate_regularisation;
        match self.m.rheology {
            Rheology::Kinetic(kt) => {
                let salt = kt.saltation_enabled();
                for i in 0..n {
                    let phi = self.phi[i].max(0.0);
                    let t = self.temp[i].max(0.0);
                    let st = t.sqrt();
                    let input =
                        SaltationInput { sqrt_t: st, k_drag: self.k_drag[i], particle_density: c.rho_p, diameter: c.d };
                    let co = kt.coefficients(phi, if salt { Some(&input) } else { None });
                    self.coef[i] = co;
                    // dF1/dphi by a one-sided difference away from phi_max (F1 is convex
                    // and >= phi, so the slope is >= F1/phi, the dilute limit 1)
                    let h = 1e-7;
                    let f1p = if phi + h < kt.phi_max() {
                        (kt.coefficients(phi + h, None).f1 - co.f1) / h
                    } else {
                        co.f1 / phi.max(1e-12)
                    };
                    self.f1_slope[i] = f1p.max(0.0);
                    self.pres[i] = self.kinetic_pressure(kt, i, t);
                    self.eta_kin[i] = c.rho_p * c.d * co.f2 * st;
                    self.kappa[i] = c.rho_p * c.d * co.f3 * st;
                }
                let mu_s = kt.static_friction();
                for j in 0..=n {
                    let (l, rr) = (j.saturating_sub(1), j.min(n - 1));
                    let g = self.face_gamma[j];
                    let eta = 0.5 * (self.eta_kin[l] + self.eta_kin[rr]);
                    let p_el = 0.5 * (self.pres[l].p_el + self.pres[rr].p_el);
                    let (tc, sec) = coulomb(mu_s * p_el, g, r);
                    self.eta_face[j] = eta + sec;
                    self.sigma_face[j] = 0.0;
                    self.tau_p[j] = eta * g + tc;
                }
            }
            Rheology::Local { model, elastic } => {
                self.local_pressures(model, elastic);
                self.surface_overburden();
                for j in 0..=n {
                    let (l, rr) = (j.saturating_sub(1), j.min(n - 1));
                    let g = self.face_gamma[j];
                    let p = 0.5 * (self.pres[l].p + self.overburden[l] + self.pres[rr].p + self.overburden[rr]);
                    let mu = model.friction(model.control_number(&self.local_state(g, p)));
                    let (t0, sec) = coulomb(mu * p, g, r);
                    self.eta_face[j] = sec;
                    self.sigma_face[j] = 0.0;
                    self.tau_p[j] = t0;
                }
            }
        }
        self.tau_p[n] = 0.0;
    }

    /// Pressure of a local rheology at every cell from the current phi and the cell shear
    /// rate of the current u_p, linearised in phi.
    fn local_pressures(&mut self, model: &dyn saltus_core::LocalRheology, elastic: Elastic) {
        for i in 0..self.len() {
            let phi = self.phi[i].max(0.0);
            let st = self.local_state(self.gamma_p[i], 0.0);
            let p = Rheology::local_pressure(model, &elastic, &st, phi);
            let dphi = 1e-7;
            let a = if phi + dphi < elastic.phi_max {
                ((Rheology::local_pressure(model, &elastic, &st, phi + dphi) - p) / dphi).max(0.0)
            } else {
                elastic.derivative(phi)
            };
            let p_el = elastic.pressure(phi);
            self.pres[i] = super::rheology::Pressure { p, p_el, a, b: p - a * phi };
        }
    }

    /// Overburden of local rheologies: the weight the volume-fraction flux cannot bring into
    /// the discrete wall-normal balance. The well-balanced flux makes each face carry
    /// p_L - p_R = gw h (phi_L + phi_R)/2 at steady state, but at the free surface of a dense
    /// layer the face between the last cell with grains and the empty cell above has no
    /// grains upwind of the settling velocity: its flux vanishes whatever the imbalance
    /// (r = 0 in `well_balanced_face`), and the dilatancy pressure of the partly filled
    /// surface cell, evaluated as if its grains were spread over the cell, is far below the
    /// weight of its upper half (0.22 Pa against 0.79 Pa in the dry incline at 100 cells).
    /// The missing weight, gw h phi_c + p_R - p_L at such a face (weighted by 1 - r, so that
    /// it fades where the flux can act and is zero at faces in balance), is added to the
    /// pressure the momentum step sees in every cell below. It is constant below the face,
    /// so the phi step, which sees pressure differences only, is unchanged.
    fn surface_overburden(&mut self) {
        let n = self.len();
        let gw = self.c.buoyant_weight;
        let mut sum = 0.0;
        self.overburden[n - 1] = 0.0;
        for j in (1..n).rev() {
            let (l, r) = (j - 1, j);
            let (phi_l, phi_r) = (self.phi[l].max(0.0), self.phi[r].max(0.0));
            let phi_c = 0.5 * (phi_l + phi_r);
            let force = gw * phi_c * self.h[j] + self.pres[r].p - self.pres[l].p;
            if phi_c > 0.0 && force > 0.0 && force.is_finite() {
                let (ratio, _) = self.well_balanced_face(j, 1.0, gw, self.pres[l].p, self.pres[r].p);
                sum += (1.0 - ratio.min(1.0)).max(0.0) * force;
            }
            self.overburden[l] = sum;
        }
    }

    /// After the momentum step of a local rheology: the shear rates of the new u_p and the
    /// pressure at them, so that the phi step balances the weight with the dilatancy
    /// pressure of the shear rate the momentum step just produced (the analogue of the
    /// kinetic path, whose phi step sees the new temperature). With the shear rate of the
    /// start of the step instead, the momentum step of the next step sees a pressure off the
    /// balance by (gamma_new / gamma_old)^2, and since mu(I) is flat (a stress-ratio error
    /// of 0.4 % is an I error of 1.6 %) that loop amplifies: the profiles never settle.
    fn update_local_pressure(&mut self) {
        let Rheology::Local { model, elastic } = self.m.rheology else { return };
        self.shear_rates();
        self.local_pressures(model, elastic);
    }

    /// Particle pressure of cell `i` at temperature `t`, linearised in phi:
    /// p_el + rho_p F1 T with slope p_el' + rho_p T F1'.
    fn kinetic_pressure(&self, kt: &dyn saltus_core::KineticTheory, i: usize, t: f64) -> super::rheology::Pressure {
        let phi = self.phi[i].max(0.0);
        let p_el = kt.elastic_pressure(phi);
        let a = kt.elastic_pressure_derivative(phi) + self.c.rho_p * t * self.f1_slope[i];
        let p = p_el + self.c.rho_p * self.coef[i].f1 * t;
        super::rheology::Pressure { p, p_el, a, b: p - a * phi }
    }

    /// Backward-Euler step of the coupled streamwise momentum of both phases.
    fn solve_momentum(&mut self, dt: f64) -> Result<(), Breakdown> {
        let n = self.len();
        let c = self.c;
        let inv_dt = 1.0 / dt;
        let bl = &mut self.block;
        for i in 0..n {
            let phi = self.phi[i].max(0.0);
            let eps = 1.0 - phi;
            let dz = self.dz[i];
            let phim = phi.max(PHI_FLOOR);
            // drag linearised about the old slip: beta_t (u_f - u_p) + (beta - beta_t) slip_old
            let tangent = self.drag_tangent[i];
            let bf = self.beta[i] * dz;
            let bp = phim * eps * self.k_drag[i] * dz;
            let slip = self.uf[i] - self.up[i];
            let mf = eps * c.rho_f * dz * inv_dt;
            let mp = phim * c.rho_p * dz * inv_dt;
            bl.diag[i] = [[mf + tangent * bf, -tangent * bf], [-tangent * bp, mp + tangent * bp]];
            bl.lower[i] = [0.0; 2];
            bl.upper[i] = [0.0; 2];
            bl.rhs[i] = [
                mf * self.uf[i] + eps * (c.rho_f * c.gx + c.grad) * dz + (tangent - 1.0) * bf * slip,
                mp * self.up[i] + phim * (c.rho_p * c.gx + c.grad) * dz + self.sigma_face[i + 1]
                    - self.sigma_face[i]
                    - (tangent - 1.0) * bp * slip,
            ];
        }
        for j in 1..n {
            let cf = self.fluid_cond[j];
            let cp = self.eta_face[j] / self.h[j];
            bl.diag[j - 1][0][0] += cf;
            bl.diag[j - 1][1][1] += cp;
            bl.upper[j - 1] = [-cf, -cp];
            bl.diag[j][0][0] += cf;
            bl.diag[j][1][1] += cp;
            bl.lower[j] = [-cf, -cp];
        }
        // bottom no-slip for both phases: stress = k (c_a u_0 + c_b u_1)
        let wf = c.rho_f * self.fluid_k[0];
        let wp = self.eta_face[0];
        bl.diag[0][0][0] += wf * self.wall[0];
        bl.upper[0][0] += wf * self.wall[1];
        bl.diag[0][1][1] += wp * self.wall[0];
        bl.upper[0][1] += wp * self.wall[1];
        if self.cfg.domain.top == Top::Lid {
            let u = self.cfg.domain.lid_velocity;
            let w = c.rho_f * self.fluid_k[n - 1];
            let [cw, ca, cb] = self.top_wall;
            bl.diag[n - 1][0][0] += w * ca;
            bl.lower[n - 1][0] += w * cb;
            bl.rhs[n - 1][0] -= w * cw * u;
        }
        if let Err(row) = bl.solve(&mut self.xb) {
            return Err(self.breakdown(row, "u_f", f64::NAN, "singular momentum system".into()));
        }
        for i in 0..n {
            let [a, b] = self.xb[i];
            if !a.is_finite() {
                return Err(self.breakdown(i, "u_f", a, "not finite after the momentum solve".into()));
            }
            if !b.is_finite() {
                return Err(self.breakdown(i, "u_p", b, "not finite after the momentum solve".into()));
            }
            self.uf[i] = a;
            self.up[i] = b;
        }
        Ok(())
    }

    /// Backward-Euler step of the granular temperature (eq 2.16 with 2.18-2.25 or 3.13):
    /// production from the new shear rate, conduction, collisional and drag dissipation
    /// implicit, so T stays >= 0.
    fn solve_temperature(&mut self, dt: f64) -> Result<(), Breakdown> {
        let Rheology::Kinetic(kt) = self.m.rheology else { return Ok(()) };
        let n = self.len();
        let c = self.c;
        // shear rate of the new particle velocity
        let mut below = 0.0;
        for i in 0..n {
            let above = if i + 1 < n { 0.5 * (self.up[i] + self.up[i + 1]) } else { self.up[n - 1] };
            self.gamma_p[i] = (above - below) / self.dz[i];
            below = above;
        }
        let t = &mut self.tri;
        for i in 0..n {
            let phi = self.phi[i].max(0.0);
            let m = 1.5 * c.rho_p * phi.max(PHI_FLOOR) * self.dz[i] / dt;
            let st = self.temp[i].max(0.0).sqrt();
            let jfac =
                kt.drag_dissipation_factor(self.m.drag.cd_inf(), self.m.drag.cd_inf() / self.cd_ratio[i].max(1e-300));
            let sink = c.rho_p / c.d * self.coef[i].f4 * st + jfac * self.beta[i];
            let prod = self.eta_kin[i] * self.gamma_p[i] * self.gamma_p[i];
            t.lower[i] = 0.0;
            t.upper[i] = 0.0;
            t.diag[i] = m + sink * self.dz[i];
            t.rhs[i] = m * self.temp[i].max(0.0) + prod * self.dz[i];
        }
        for j in 1..n {
            let k = 0.5 * (self.kappa[j - 1] + self.kappa[j]) / self.h[j];
            t.diag[j - 1] += k;
            t.upper[j - 1] -= k;
            t.diag[j] += k;
            t.lower[j] -= k;
        }
        if let Err(row) = t.solve(&mut self.work) {
            return Err(self.breakdown(row, "theta_g", f64::NAN, "singular temperature system".into()));
        }
        for i in 0..n {
            let v = self.work[i];
            if !(v.is_finite() && v >= -1e-300) {
                return Err(self.breakdown(i, "theta_g", v, "granular temperature not finite or negative".into()));
            }
            self.temp[i] = v.max(0.0);
        }
        // the phi step sees the new temperature
        for i in 0..n {
            self.pres[i] = self.kinetic_pressure(kt, i, self.temp[i]);
        }
        Ok(())
    }

    /// Implicit step of the sediment mass (eq 2.2) with the wall-normal particle velocity of
    /// the quasi-static wall-normal momentum balance (eqs 2.5-2.6):
    /// phi w_p = -(eps/K) [phi (rho_p - rho_f) g cos + dp_p/dz] - eps D dphi/dz.
    fn solve_phi(&mut self, dt: f64) -> Result<(), Breakdown> {
        let n = self.len();
        let gw = self.c.buoyant_weight;
        // local rheologies: the well-balanced deferred correction (see
        // `well_balanced_correction`); kinetic theory keeps the MUSCL one
        let well_balanced = matches!(self.m.rheology, Rheology::Local { .. });
        // face coefficients: F_j = cl phi_L + cr phi_R + s
        let mut coeffs = std::mem::take(&mut self.face_coeffs);
        coeffs.clear();
        coeffs.resize(3 * (n + 1), 0.0);
        for j in 1..n {
            let (l, r) = (j - 1, j);
            let h = self.h[j];
            let up = if gw >= 0.0 { r } else { l };
            let m = self.mobility[up];
            let dd = 0.5 * ((1.0 - self.phi[l]) * self.drift[l] + (1.0 - self.phi[r]) * self.drift[r]);
            let (pl, pr) = (self.pres[l], self.pres[r]);
            // local rheologies: factor r on the pressure part of the flux and the deferred
            // correction of the weight; kinetic theory: r = 1 and the MUSCL correction below
            let wb = if well_balanced { Some(self.well_balanced_face(j, m, gw, pl.p, pr.p)) } else { None };
            let mp = m * wb.map_or(1.0, |w| w.0);
            let mut cl = mp * pl.a / h + dd / h;
            let mut cr = -mp * pr.a / h - dd / h;
            if up == r {
                cr -= m * gw;
            } else {
                cl -= m * gw;
            }
            // second-order settling at steady state: the implicit upwind value plus a
            // deferred MUSCL correction with the minmod limiter (zero at an interface with
            // clear fluid, so phi stays >= 0); the steady balance is then
            // dp/dz = -phi_face (rho_p - rho_f) g cos to second order
            let (down, upv, beyond) = if up == r {
                (self.phi[l], self.phi[r], if r + 1 < n { self.phi[r + 1] } else { self.phi[r] })
            } else {
                (self.phi[r], self.phi[l], if l > 0 { self.phi[l - 1] } else { self.phi[l] })
            };
            let correction = 0.5 * minmod(down - upv, upv - beyond);
            let deferred = wb.map_or(-m * gw * correction, |w| w.1);
            coeffs[3 * j] = cl;
            coeffs[3 * j + 1] = cr;
            coeffs[3 * j + 2] = -mp * (pr.b - pl.b) / h + deferred;
        }
        let t = &mut self.tri;
        for i in 0..n {
            let m = self.dz[i] / dt;
            let (cl_up, cr_up, s_up) = (coeffs[3 * (i + 1)], coeffs[3 * (i + 1) + 1], coeffs[3 * (i + 1) + 2]);
            let (cl_dn, cr_dn, s_dn) = (coeffs[3 * i], coeffs[3 * i + 1], coeffs[3 * i + 2]);
            t.diag[i] = m + cl_up - cr_dn;
            t.upper[i] = cr_up;
            t.lower[i] = -cl_dn;
            // delta form: the right side is minus the divergence of the fluxes at the old
            // phi, a telescoping sum, so the mass change is round-off of the increment
            let f_up = cl_up * self.phi[i] + if i + 1 < n { cr_up * self.phi[i + 1] } else { 0.0 } + s_up;
            let f_dn = if i > 0 { cl_dn * self.phi[i - 1] } else { 0.0 } + cr_dn * self.phi[i] + s_dn;
            t.rhs[i] = f_dn - f_up;
        }
        if let Err(row) = t.solve(&mut self.work) {
            self.face_coeffs = coeffs;
            return Err(self.breakdown(row, "phi", f64::NAN, "singular volume-fraction system".into()));
        }
        // fluxes of the implicit solution, then phi rebuilt from them in flux form: the
        // same solution up to the round-off of the solve, but the mass changes only by the
        // round-off of a telescoping sum, however ill-conditioned the stiff system is
        for i in 0..n {
            self.work[i] += self.phi[i];
        }
        self.flux[0] = 0.0;
        self.flux[n] = 0.0;
        for j in 1..n {
            self.flux[j] = coeffs[3 * j] * self.work[j - 1] + coeffs[3 * j + 1] * self.work[j] + coeffs[3 * j + 2];
        }
        for i in 0..n {
            self.work[i] = self.phi[i] - dt / self.dz[i] * (self.flux[i + 1] - self.flux[i]);
        }
        let phi_max = self.m.rheology.phi_max();
        for i in 0..n {
            let v = self.work[i];
            let bad = if !v.is_finite() {
                Some("not finite")
            } else if v < -1e-9 {
                Some("negative")
            } else if v >= phi_max {
                Some("at or above the maximum packing of the granular closure")
            } else if (v - self.phi[i]).abs() > self.cfg.settings.max_phi_change {
                Some("changed more than solver.max_phi_change in one step")
            } else {
                None
            };
            if let Some(reason) = bad {
                self.face_coeffs = coeffs;
                return Err(self.breakdown(i, "phi", v, reason.into()));
            }
        }
        self.phi.copy_from_slice(&self.work);
        self.face_coeffs = coeffs;
        Ok(())
    }

    /// Backward-Euler step of k and omega of the two-equation closure (Cheng et al. eqs
    /// 21-35) with the shear rate of the new fluid velocity; nothing without such a closure.
    fn solve_two_equation(&mut self, dt: f64) -> Result<(), Breakdown> {
        let Some(kw) = self.kw.as_mut() else { return Ok(()) };
        let n = self.phi.len();
        let c = self.c;
        let mut below = 0.0;
        for i in 0..n {
            let above = if i + 1 < n { face_value(&self.zc, &self.zf, &self.uf, i + 1) } else { self.uf[n - 1] };
            kw.shear[i] = (above - below) / self.dz[i];
            below = above;
        }
        for i in 0..n {
            let (l, r) = (i.saturating_sub(1), (i + 1).min(n - 1));
            kw.dphidz[i] = (self.phi[r] - self.phi[l]) / (self.zc[r] - self.zc[l]);
            // beta of Cheng eq 23 = phi eps K / phi
            kw.drag[i] = self.k_drag[i] * (1.0 - self.phi[i].clamp(0.0, 1.0));
        }
        let wall_gradient = self.wall[0] * self.uf[0] + self.wall[1] * self.uf[1];
        let wall_u_star = (c.nu_f * self.visc_ratio[0] * wall_gradient.abs()).sqrt();
        let input = TwoEquationInput {
            col: ColumnView {
                z: &self.zc,
                dz: &self.dz,
                phi: &self.phi,
                dudz: &kw.shear,
                diameter: c.d,
                nu_f: c.nu_f,
                transported: &[],
            },
            drag: &kw.drag,
            dphidz: &kw.dphidz,
            fluid_density: c.rho_f,
            particle_density: c.rho_p,
            gravity_normal: kw.gravity_normal,
            friction_velocity: kw.u_star,
        };
        let geometry = ColumnGeometry { z: &self.zc, dz: &self.dz };
        let result = kw.col.advance(kw.model, &input, geometry, wall_u_star, dt);
        result.map_err(|f| self.breakdown(f.cell, f.field, f.value, f.reason.into()))
    }

    /// Turbulent kinetic energy and specific dissipation rate per cell, when the
    /// turbulence closure transports them.
    pub fn k_omega(&self) -> Option<(&[f64], &[f64])> {
        self.kw.as_ref().map(|kw| (kw.col.k.as_slice(), kw.col.omega.as_slice()))
    }

    /// Well-balanced volume-fraction flux of local rheologies at interior face `j`, from the
    /// old state: the factor r on the pressure part of the implicit flux and the deferred
    /// correction of its weight. The flux of the wall-normal balance (Chassagne 2023 eqs
    /// 2.5-2.6) is written with the weight of the central volume fraction
    /// phi_c = (phi_L + phi_R)/2, carried at the velocity w = -m [gw phi_c + dp/dz] / phi_c
    /// and transported with the MUSCL (minmod) value phi_w of phi upwind of w:
    ///   F = w phi_w = -m [gw phi_w + r dp/dz],  r = phi_w / phi_c,
    /// with r and phi_w frozen over the step, dp/dz implicit (linearised in phi) and the
    /// weight as the implicit upwind -m gw phi_up plus the deferred -m gw (phi_w - phi_up).
    /// At steady state w = 0, so the discrete balance is the central one,
    /// p_R - p_L = -gw h (phi_L + phi_R)/2, whose sum makes the pressure at each cell centre
    /// exactly the weight above it whatever the shape of phi ("well balanced", as the
    /// hydrostatic reconstruction of Audusse et al. 2004 for shallow water). The MUSCL
    /// correction of the weight alone limits phi_face towards the upper cell across the free
    /// surface of a dense layer, where phi drops from 0.55 to 0 in two cells; the steady
    /// pressure under it then misses part of the weight of the surface cells (0.7 Pa of 236
    /// in the dry incline at 100 cells), a first-order error that the flat mu(I) turns into
    /// four times as large an error of the shear rate over the whole layer. Where the
    /// pressure gradient vanishes (dilute settling) w = -m gw, phi_w is the MUSCL value of
    /// the upper cell and the flux is the MUSCL one exactly. Returns (r, deferred flux).
    fn well_balanced_face(&self, j: usize, m: f64, gw: f64, pl: f64, pr: f64) -> (f64, f64) {
        let n = self.len();
        let (l, r) = (j - 1, j);
        let (phi_l, phi_r) = (self.phi[l].max(0.0), self.phi[r].max(0.0));
        let phi_c = 0.5 * (phi_l + phi_r);
        let force = gw * phi_c + (pr - pl) / self.h[j];
        if !(phi_c > 0.0 && force.is_finite()) {
            // no grains on either side (or an infinite pressure, which the phi step then
            // rejects): the upwind flux
            return (1.0, 0.0);
        }
        let up_g = if gw >= 0.0 { phi_r } else { phi_l };
        // MUSCL value upwind of w: the upper cell when force > 0 (w < 0, downwards)
        let phi_w = if force > 0.0 {
            let beyond = if r + 1 < n { self.phi[r + 1] } else { phi_r };
            phi_r + 0.5 * minmod(phi_l - phi_r, phi_r - beyond)
        } else {
            let beyond = if l > 0 { self.phi[l - 1] } else { phi_l };
            phi_l + 0.5 * minmod(phi_r - phi_l, phi_l - beyond)
        };
        (phi_w / phi_c, -m * gw * (phi_w - up_g))
    }

    fn breakdown(&self, cell: usize, field: &'static str, value: f64, reason: String) -> Breakdown {
        Breakdown { time: self.time, cell, z: self.zc.get(cell).copied().unwrap_or(f64::NAN), field, value, reason }
    }

    fn save(&mut self) {
        if let Some(kw) = &mut self.kw {
            kw.col.save();
        }
        let [a, b, c, d, e] = &mut self.saved;
        for (dst, src) in [(a, &self.phi), (b, &self.uf), (c, &self.up), (d, &self.temp), (e, &self.flux)] {
            dst.clear();
            dst.extend_from_slice(src);
        }
    }

    fn restore(&mut self) {
        if let Some(kw) = &mut self.kw {
            kw.col.restore();
        }
        let [a, b, c, d, e] = &self.saved;
        self.phi.copy_from_slice(a);
        self.uf.copy_from_slice(b);
        self.up.copy_from_slice(c);
        self.temp.copy_from_slice(d);
        self.flux.copy_from_slice(e);
    }

    fn attempt(&mut self, dt: f64) -> Attempt {
        self.save();
        self.evaluate();
        let result = self
            .solve_momentum(dt)
            .and_then(|_| {
                if self.kinetic {
                    self.solve_temperature(dt)
                } else {
                    self.update_local_pressure();
                    Ok(())
                }
            })
            .and_then(|_| self.solve_two_equation(dt))
            .and_then(|_| self.solve_phi(dt));
        match result {
            Ok(()) => Attempt::Accepted,
            Err(b) => {
                self.restore();
                Attempt::Rejected(b)
            }
        }
    }

    /// Largest relative rate of change (1/s) between the saved and the current state, and
    /// the factor by which dt may grow. Particle fields are weighted by phi (changes of
    /// phi u_p and phi T relative to their maxima), so that the velocity and temperature of
    /// the vanishing particles of the clear-fluid region, which carry nothing, do not hold
    /// the run away from steady state.
    fn rates(&self, dt: f64) -> (f64, f64) {
        let [phi0, uf0, up0, t0, _] = &self.saved;
        let n = self.len();
        let mut du: f64 = 0.0;
        let mut dq: f64 = 0.0;
        let mut de: f64 = 0.0;
        let mut dphi: f64 = 0.0;
        let (mut umax, mut qmax, mut emax, mut phimax) = (1e-300f64, 1e-300f64, 1e-300f64, 1e-300f64);
        for i in 0..n {
            let phi = self.phi[i].max(0.0);
            du = du.max((self.uf[i] - uf0[i]).abs());
            dq = dq.max(phi * (self.up[i] - up0[i]).abs());
            de = de.max(phi * (self.temp[i] - t0[i]).abs());
            dphi = dphi.max((self.phi[i] - phi0[i]).abs());
            umax = umax.max(self.uf[i].abs());
            qmax = qmax.max(phi * self.up[i].abs());
            emax = emax.max(phi * self.temp[i]);
            phimax = phimax.max(phi);
        }
        let mut rel = (du / umax).max(dphi / phimax);
        if let Some(kw) = &self.kw {
            rel = rel.max(two_equation_change(&kw.col.k, kw.col.saved_k()));
        }
        if qmax > 1e-300 {
            rel = rel.max(dq / qmax);
        }
        if self.kinetic {
            rel = rel.max(de / emax);
        }
        // growth: aim at phi changes of half the allowed maximum and relative changes of 0.2
        let target = (0.5 * self.cfg.settings.max_phi_change / dphi.max(1e-300)).min(0.2 / rel.max(1e-300));
        (rel / dt, target.clamp(0.5, 1.3))
    }

    /// Advance to steady state or the end time. `observer` is called after every accepted
    /// step; returning `false` from it stops the run (as at the end time).
    pub fn run(&mut self, observer: &mut dyn FnMut(&Progress) -> bool) -> Ending {
        let s = self.cfg.settings.clone();
        let mut dt = s.dt_initial.min(s.dt_max);
        let mut calm = 0usize;
        loop {
            if self.time >= s.end_time * (1.0 - 1e-12) {
                return Ending::EndTime;
            }
            if self.steps >= s.max_steps {
                return Ending::MaxSteps;
            }
            let step = dt.min(s.end_time - self.time);
            match self.attempt(step) {
                Attempt::Accepted => {
                    self.time += step;
                    self.steps += 1;
                    let (rate, grow) = self.rates(step);
                    self.residual = rate;
                    calm = if rate < s.steady_tolerance { calm + 1 } else { 0 };
                    dt = (dt * grow).min(s.dt_max);
                    let go_on = observer(&Progress {
                        time: self.time,
                        end_time: s.end_time,
                        steps: self.steps,
                        dt,
                        residual: rate,
                    });
                    if calm >= s.steady_steps {
                        return Ending::Steady;
                    }
                    if !go_on {
                        return Ending::EndTime;
                    }
                }
                Attempt::Rejected(b) => {
                    self.rejected += 1;
                    dt *= 0.3;
                    if dt < s.dt_min {
                        return Ending::Unstable(b);
                    }
                }
            }
        }
    }
}

/// Largest change of k relative to its maximum.
fn two_equation_change(k: &[f64], k0: &[f64]) -> f64 {
    let kmax = k.iter().fold(1e-300f64, |a, &b| a.max(b));
    k.iter().zip(k0).fold(0.0f64, |a, (x, y)| a.max((x - y).abs())) / kmax
}

/// Derived cell profiles, see [`Eulerian::derived`].
#[derive(Clone, Debug, Default)]
pub struct Derived {
    /// particle shear stress (Pa)
    pub tau_p: Vec<f64>,
    /// fluid shear stress, viscous + turbulent (Pa)
    pub tau_f: Vec<f64>,
    /// particle pressure (Pa)
    pub p_p: Vec<f64>,
    /// particle wall-normal velocity (m/s)
    pub w_p: Vec<f64>,
    /// inertial number I (kinetic and mu(I)) or K (mu(K))
    pub control: Vec<f64>,
}
