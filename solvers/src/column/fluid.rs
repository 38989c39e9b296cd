//! Streamwise fluid momentum of the column: [`FluidColumn`].

use saltus_core::closure::turbulence::TwoEquation;
use saltus_core::{ColumnView, Turbulence, WallFriction};

use super::bdf2::Bdf2;
use super::operator::ColumnOperator;
use super::params::{Closures, ColumnParams, Coupling, TopBoundary};
use super::tridiagonal::Tridiagonal;
use super::turbulence::{friction_velocity, EddyViscosity, KOmegaPhysics, KOmegaRun};
use super::{ColumnError, Grid};

mod steady;

/// 1D column solver of the streamwise fluid momentum; see the module documentation of
/// [`crate::column`] for the equation, the discretisation and the boundary conditions.
///
/// All work arrays are allocated by [`FluidColumn::new`]; [`FluidColumn::step`] and
/// [`FluidColumn::solve_steady`] do not allocate.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct FluidColumn {
    op: ColumnOperator,
    params: ColumnParams,
    time: f64,
    residual: f64,
    /// fluid velocity per cell
    u: Vec<f64>,
    /// fluid velocity per face
    u_face: Vec<f64>,
    /// du/dz per cell (given to the turbulence closure)
    dudz: Vec<f64>,
    /// eddy viscosity per cell (the one of the last solve, or of the converged state)
    eddy: EddyViscosity,
    /// nu_eff / nu_f per cell
    ratio: Vec<f64>,
    /// eps (nu_eff + nu_t) per cell (m^2/s)
    k: Vec<f64>,
    /// rho_f times the harmonic face diffusivity over the centre distance (kg m^-2 s^-1),
    /// interior faces 1..n (entries 0 and n unused)
    cond: Vec<f64>,
    /// total shear stress per face (Pa)
    stress: Vec<f64>,
    /// inputs of the last step
    phi: Vec<f64>,
    beta: Vec<f64>,
    u_p: Vec<f64>,
    /// driving per unit volume eps (rho_f g sin(alpha) + G_x) per cell (Pa/m)
    source: Vec<f64>,
    /// side-wall friction coefficient gamma_w per cell (kg m^-3 s^-1), lagged like nu_t;
    /// empty without side walls (a checkpoint of a column without them has none)
    #[serde(default)]
    wall: Vec<f64>,
    tri: Tridiagonal,
    /// k and omega of a two-equation closure, allocated on the first step with one
    kw: Option<KOmegaRun>,
    /// beta of Cheng et al. eq 23 per unit particle volume given by the caller for the
    /// drag damping of k and omega ([`FluidColumn::set_damping_drag`]); empty: the
    /// exchange's beta over phi
    #[serde(default)]
    damping: Vec<f64>,
    /// no step taken yet: the first nu_t is taken unrelaxed
    fresh: bool,
    /// [`FluidColumn::step_bdf2`]: the velocity before the last step and that step's
    /// length (s, 0 before the first)
    #[serde(default)]
    previous: Vec<f64>,
    #[serde(default)]
    previous_dt: f64,
    /// the velocity at the start of a BDF2 step (scratch)
    #[serde(skip)]
    start: Vec<f64>,
}

impl FluidColumn {
    /// A column at rest (u = 0, t = 0, clear water) on `grid`.
    pub fn new(grid: Grid, params: ColumnParams) -> Result<Self, ColumnError> {
        params.validate()?;
        let n = grid.len();
        let mut col = Self {
            params,
            time: 0.0,
            residual: 0.0,
            u: vec![0.0; n],
            u_face: vec![0.0; n + 1],
            dudz: vec![0.0; n],
            eddy: EddyViscosity::new(n, params.relaxation),
            ratio: vec![1.0; n],
            k: vec![0.0; n],
            cond: vec![0.0; n + 1],
            stress: vec![0.0; n + 1],
            phi: vec![0.0; n],
            beta: vec![0.0; n],
            u_p: vec![0.0; n],
            source: vec![0.0; n],
            wall: if params.side_walls.is_some() { vec![0.0; n] } else { Vec::new() },
            tri: Tridiagonal::new(n),
            kw: None,
            damping: Vec::new(),
            fresh: true,
            previous: Vec::new(),
            previous_dt: 0.0,
            start: Vec::new(),
            op: ColumnOperator::new(grid),
        };
        let s = col.params.density * col.params.gravity_x + col.params.pressure_gradient;
        col.source.fill(s);
        col.update_coefficients();
        col.update_derived();
        Ok(col)
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        self.op.grid()
    }

    /// The discrete operator.
    pub fn operator(&self) -> &ColumnOperator {
        &self.op
    }

    /// The parameters.
    pub fn params(&self) -> &ColumnParams {
        &self.params
    }

    /// Simulated time (s), advanced by [`FluidColumn::step`] with a finite dt.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Set the imposed pressure gradient G_x = -dp/dx (Pa/m) of the next steps: a forcing
    /// that varies in time. A non-finite value is refused.
    pub fn set_pressure_gradient(&mut self, g: f64) -> Result<(), ColumnError> {
        if !g.is_finite() {
            return Err(ColumnError::InvalidParameter {
                name: "pressure_gradient",
                value: g,
                reason: "must be finite",
            });
        }
        self.params.pressure_gradient = g;
        Ok(())
    }

    /// Set the simulated time (s), e.g. on restart.
    pub fn set_time(&mut self, t: f64) {
        self.time = t;
    }

    /// Fluid velocity u_f per cell (m/s).
    pub fn velocity(&self) -> &[f64] {
        &self.u
    }

    /// Set the fluid velocity per cell (initial condition); face values, shear rate and
    /// stresses are updated with the current coefficients.
    pub fn set_velocity(&mut self, u: &[f64]) -> Result<(), ColumnError> {
        let n = self.u.len();
        if u.len() != n {
            return Err(ColumnError::Length { field: "u_f", expected: n, found: u.len() });
        }
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(self.invalid("u_f", i, u[i], "must be finite"));
        }
        self.u.copy_from_slice(u);
        self.update_derived();
        Ok(())
    }

    /// Fluid velocity at the faces z_f[0..=n] (m/s): 0 at the wall; inside, the value
    /// that makes the two half-cell fluxes equal, (w_L u_L + w_R u_R) / (w_L + w_R) with
    /// w = k / (distance to the face) (linear interpolation for uniform k, exact for a
    /// piecewise-linear profile across a jump of k at the face); at the top the lid
    /// velocity or the zero-slope quadratic extrapolation of the last two cells.
    pub fn face_velocity(&self) -> &[f64] {
        &self.u_face
    }

    /// Shear rate du_f/dz per cell (1/s) handed to the turbulence closure: the difference
    /// over the cell of the linearly interpolated face values (wall 0, top as in
    /// [`FluidColumn::face_velocity`]), i.e. the central difference on a uniform grid.
    pub fn shear_rate(&self) -> &[f64] {
        &self.dudz
    }

    /// Eddy viscosity nu_t per cell (m^2/s): the one of the last linear solve (lagged)
    /// after [`FluidColumn::step`], the one of the converged velocity after
    /// [`FluidColumn::solve_steady`].
    pub fn eddy_viscosity(&self) -> &[f64] {
        self.eddy.values()
    }

    /// Turbulent kinetic energy k (m^2/s^2) and specific dissipation rate omega (1/s) per
    /// cell of a two-equation closure; `None` before the first step with one.
    pub fn k_omega(&self) -> Option<(&[f64], &[f64])> {
        self.kw.as_ref().map(|kw| (kw.col.k.as_slice(), kw.col.omega.as_slice()))
    }

    /// Give the drag coefficient beta of Cheng et al. eq 23 (per unit particle volume,
    /// kg m^-3 s^-1, one per cell) that the drag damping of k and omega takes from the next
    /// step on, instead of the exchange's beta over phi (a DEM coupling whose closure
    /// averages the relative velocity in time, eq 24). A slice of another length goes back
    /// to the exchange's.
    pub fn set_damping_drag(&mut self, beta: &[f64]) {
        self.damping.clear();
        if beta.len() == self.u.len() {
            self.damping.extend_from_slice(beta);
        }
    }

    /// The exchange's implicit drag coefficient beta per cell of the last step (kg m^-3
    /// s^-1, per unit mixture volume, [`Coupling::beta`]).
    pub fn exchange_drag(&self) -> &[f64] {
        &self.beta
    }

    /// Terms of the k and omega equations of the last step (the closure's, at k and omega
    /// of the start of that step); `None` before the first step with a two-equation closure.
    pub fn two_equation_terms(&self) -> Option<&saltus_core::closure::turbulence::TwoEquationTerms> {
        self.kw.as_ref().map(|kw| kw.col.terms())
    }

    /// beta of Cheng et al. eq 23 per cell (kg m^-3 s^-1) that the last step of k and omega
    /// took; `None` before the first step with a two-equation closure.
    pub fn damping_drag(&self) -> Option<&[f64]> {
        self.kw.as_ref().map(|kw| kw.drag.as_slice())
    }

    /// eps (nu_eff + nu_t) per cell (m^2/s), the kinematic diffusivity of the momentum
    /// equation.
    pub fn diffusivity(&self) -> &[f64] {
        &self.k
    }

    /// Total (viscous + turbulent) fluid shear stress rho_f eps (nu_eff + nu_t) du/dz per
    /// face z_f[0..=n] (Pa), as the discrete fluxes of the momentum equation.
    pub fn shear_stress(&self) -> &[f64] {
        &self.stress
    }

    /// Wall shear stress rho_f eps (nu_eff + nu_t) du/dz at z = 0 (Pa).
    pub fn wall_shear_stress(&self) -> f64 {
        self.stress[0]
    }

    /// Reynolds shear stress per cell R_xz = rho_f eps nu_t du/dz (Pa) into `out`
    /// (length n; extra entries untouched).
    pub fn reynolds_stress(&self, out: &mut [f64]) {
        let rho = self.params.density;
        for (((o, &nu), &g), &phi) in out.iter_mut().zip(self.eddy.values()).zip(&self.dudz).zip(&self.phi) {
            *o = rho * (1.0 - phi) * nu * g;
        }
    }

    /// Depth-averaged fluid velocity over the whole column, sum(u dz) / H (m/s).
    pub fn depth_averaged_velocity(&self) -> f64 {
        let q: f64 = self.u.iter().zip(self.op.grid().dz()).map(|(u, dz)| u * dz).sum();
        q / self.op.grid().height()
    }

    /// Driving per unit volume eps (rho_f g sin(alpha) + G_x) per cell (Pa/m), for the
    /// inputs of the last step.
    pub fn driving(&self) -> &[f64] {
        &self.source
    }

    /// Side-wall friction coefficient gamma_w per cell (kg m^-3 s^-1) of the last step (the
    /// walls remove gamma_w u_f per unit volume; [`super::side_walls`]); empty without
    /// side walls.
    pub fn side_wall_coefficients(&self) -> &[f64] {
        &self.wall
    }

    /// Friction of the two side walls on the fluid per unit bed area, sum_i gamma_w,i u_i
    /// dz_i (Pa): at steady state the driving equals the bed shear stress, the drag on the
    /// particles and this. 0 without side walls.
    pub fn side_wall_stress(&self) -> f64 {
        let dz = self.op.grid().dz();
        self.wall.iter().zip(&self.u).zip(dz).map(|((g, u), dz)| g * u * dz).sum()
    }

    /// Relative residual of the discrete steady equation for the current velocity and the
    /// stored nu_t: max_i |tau_{i+1/2} - tau_{i-1/2} + (S_i - D_i) dz_i| divided by
    /// |tau_wall| + |tau_top| + sum_i (|S_i| + |D_i|) dz_i, with the drag and side-wall
    /// friction D_i = beta_i (u_i - u_p,i) + gamma_w,i u_i (0 when every term vanishes). After a transient step it measures the remaining
    /// unsteadiness.
    pub fn residual(&self) -> f64 {
        self.residual
    }

    /// Advance by `dt` (s) with backward Euler: diffusion and drag implicit, nu_t lagged
    /// (evaluated once from the velocity at the start of the step and relaxed by
    /// [`ColumnParams::relaxation`] after the first step). `dt = f64::INFINITY`
    /// solves the steady equation with the lagged nu_t (one Picard iteration); time is
    /// advanced only for finite `dt`.
    pub fn step(&mut self, dt: f64, coupling: &Coupling<'_>, closures: &Closures<'_>) -> Result<(), ColumnError> {
        self.advance(dt, coupling, closures, None)
    }

    /// Advance by a finite `dt` (s) with the variable-step second-order backward
    /// differentiation formula (BDF2; Hairer & Wanner, Solving ODEs II, section III.5):
    /// (1 + 2w)/(1 + w) u^{n+1} - (1 + w) u^n + w^2/(1 + w) u^{n-1} = dt L(u^{n+1}) with
    /// w = dt / dt_{n-1}, the coefficients lagged as in [`FluidColumn::step`]; the first
    /// step (no u^{n-1} yet) is backward Euler. Second order in time for a laminar column
    /// (docs/verification.md, the Stokes layer); k and omega stay backward Euler.
    pub fn step_bdf2(&mut self, dt: f64, coupling: &Coupling<'_>, closures: &Closures<'_>) -> Result<(), ColumnError> {
        if !dt.is_finite() {
            return Err(ColumnError::InvalidParameter { name: "dt", value: dt, reason: "must be finite and > 0" });
        }
        let n = self.u.len();
        let w = if self.previous_dt > 0.0 && self.previous.len() == n { dt / self.previous_dt } else { 0.0 };
        self.start.clear();
        self.start.extend_from_slice(&self.u);
        self.advance(dt, coupling, closures, Some(w))?;
        std::mem::swap(&mut self.previous, &mut self.start);
        self.previous_dt = dt;
        Ok(())
    }

    /// One step of backward Euler, or of BDF2 with the step ratio `bdf2`.
    fn advance(
        &mut self,
        dt: f64,
        coupling: &Coupling<'_>,
        closures: &Closures<'_>,
        bdf2: Option<f64>,
    ) -> Result<(), ColumnError> {
        if dt.is_nan() || dt <= 0.0 {
            return Err(ColumnError::InvalidParameter { name: "dt", value: dt, reason: "must be > 0" });
        }
        self.load_inputs(coupling, closures)?;
        self.evaluate_turbulence(closures.turbulence)?;
        self.update_side_walls(closures.wall_friction);
        // the one relaxation policy of the column (also the Eulerian solver's)
        self.eddy.relax(self.fresh);
        self.fresh = false;
        self.update_coefficients();
        let t_new = if dt.is_finite() { self.time + dt } else { self.time };
        self.solve_linear(dt, t_new, bdf2)?;
        self.update_derived();
        if let Some(model) = closures.turbulence.as_two_equation() {
            // k and omega with the shear of the new velocity (as the Eulerian solver)
            self.advance_two_equation(model, dt, t_new)?;
        }
        self.time = t_new;
        Ok(())
    }

    /// Friction velocity of the forcing at the bed surface (m/s): the given one, else that
    /// of the driving over the whole column ([`friction_velocity`]).
    fn forcing_friction_velocity(&self) -> f64 {
        let p = &self.params;
        let drive = p.gravity_x + p.pressure_gradient / p.density;
        p.friction_velocity.unwrap_or_else(|| friction_velocity(drive, self.op.grid().height()))
    }

    /// H / u* of the forcing, or H^2 / nu without forcing (s).
    fn turbulent_time_scale(&self) -> f64 {
        let h = self.op.grid().height();
        let u = self.forcing_friction_velocity();
        if u > 0.0 {
            h / u
        } else {
            h * h / self.params.viscosity
        }
    }

    /// One backward-Euler step of k and omega ([`KOmegaRun::advance`]) with the current
    /// shear rate, volume fraction and drag; `time` names the time of a failure.
    fn advance_two_equation(&mut self, model: &dyn TwoEquation, dt: f64, time: f64) -> Result<(), ColumnError> {
        let physics = KOmegaPhysics {
            nu_f: self.params.viscosity,
            diameter: self.params.diameter,
            fluid_density: self.params.density,
            particle_density: self.params.particle_density,
            gravity_normal: self.params.gravity_normal,
            friction_velocity: self.forcing_friction_velocity(),
        };
        let n = self.u.len();
        let Some(kw) = self.kw.as_mut() else { return Ok(()) };
        if self.damping.len() == n {
            kw.drag.copy_from_slice(&self.damping);
        } else {
            for i in 0..n {
                // beta of eq 23 per unit particle volume: the coupling's beta is per unit
                // mixture volume, phi times it; it only enters multiplied by phi again
                let phi = self.phi[i];
                kw.drag[i] = if phi > 1e-12 { self.beta[i] / phi } else { 0.0 };
            }
        }
        let result = kw.advance(model, &self.op, &physics, &self.phi, &self.u, &self.dudz, self.ratio[0], dt, None);
        let zc = self.op.grid().centres();
        result.map_err(|f| ColumnError::TwoEquation {
            field: f.field,
            cell: f.cell,
            z: zc[f.cell.min(n - 1)],
            value: f.value,
            reason: f.reason,
            time,
        })
    }

    fn invalid(&self, field: &'static str, cell: usize, value: f64, reason: &'static str) -> ColumnError {
        ColumnError::InvalidInput { field, cell, z: self.op.grid().centres()[cell], value, reason }
    }

    fn non_finite(&self, field: &'static str, cell: usize, time: f64) -> ColumnError {
        ColumnError::NonFinite { field, cell, z: self.op.grid().centres()[cell], time }
    }

    /// Check and copy the coupling inputs; effective viscosity ratio and driving.
    fn load_inputs(&mut self, c: &Coupling<'_>, closures: &Closures<'_>) -> Result<(), ColumnError> {
        let n = self.u.len();
        let two_equation = closures.turbulence.as_two_equation();
        if !closures.turbulence.transported().is_empty() && two_equation.is_none() {
            return Err(ColumnError::Unsupported { model: closures.turbulence.name() });
        }
        if let (Some(_), TopBoundary::Lid { velocity }) = (two_equation, self.params.top) {
            return Err(ColumnError::InvalidParameter {
                name: "top",
                value: velocity,
                reason: "a lid has no wall treatment for k and omega; use a free surface or a symmetry plane",
            });
        }
        for (field, s) in [("phi", c.phi), ("beta", c.beta), ("u_p", c.u_p)] {
            if s.len() != n {
                return Err(ColumnError::Length { field, expected: n, found: s.len() });
            }
        }
        for i in 0..n {
            let (phi, beta, up) = (c.phi[i], c.beta[i], c.u_p[i]);
            if !(phi.is_finite() && (0.0..1.0).contains(&phi)) {
                return Err(self.invalid("phi", i, phi, "volume fraction must be in [0, 1)"));
            }
            if !(beta.is_finite() && beta >= 0.0) {
                return Err(self.invalid("beta", i, beta, "drag coefficient must be finite and >= 0"));
            }
            if !up.is_finite() {
                return Err(self.invalid("u_p", i, up, "particle velocity must be finite"));
            }
        }
        self.phi.copy_from_slice(c.phi);
        self.beta.copy_from_slice(c.beta);
        self.u_p.copy_from_slice(c.u_p);
        if let (Some(model), None) = (two_equation, &self.kw) {
            // started from the first coupling's phi: a packed bed starts without turbulence
            let (u_star, h) = (self.forcing_friction_velocity(), self.op.grid().height());
            let p = &self.params;
            self.kw = Some(KOmegaRun::new(model, &self.phi, u_star, h, p.viscosity, p.diameter));
        }
        closures.viscosity.ratio_batch(&self.phi, &mut self.ratio);
        if let Some(i) = self.ratio.iter().position(|r| !(r.is_finite() && *r > 0.0)) {
            return Err(self.invalid(
                "phi",
                i,
                self.phi[i],
                "the effective viscosity is not finite and positive at this volume fraction",
            ));
        }
        let drive = self.params.density * self.params.gravity_x + self.params.pressure_gradient;
        for (s, &phi) in self.source.iter_mut().zip(&self.phi) {
            *s = (1.0 - phi) * drive;
        }
        Ok(())
    }

    /// gamma_w of the side walls from the current velocity and phi (nothing without walls).
    fn update_side_walls(&mut self, friction: Option<&dyn WallFriction>) {
        let (Some(walls), Some(friction)) = (self.params.side_walls, friction) else { return };
        let n = self.u.len();
        if self.wall.len() != n {
            self.wall.resize(n, 0.0);
        }
        walls.coefficients(friction, self.params.density, self.params.viscosity, &self.phi, &self.u, &mut self.wall);
    }

    /// Candidate nu_t from the current shear rate.
    fn evaluate_turbulence(&mut self, turbulence: &dyn Turbulence) -> Result<(), ColumnError> {
        let kw_fields = self.kw.as_ref().map(|kw| kw.col.fields());
        let transported: &[&[f64]] = kw_fields.as_ref().map_or(&[], |f| f.as_slice());
        let col = ColumnView {
            z: self.op.grid().centres(),
            dz: self.op.grid().dz(),
            phi: &self.phi,
            dudz: &self.dudz,
            diameter: self.params.diameter,
            nu_f: self.params.viscosity,
            transported,
        };
        let result = self.eddy.evaluate(turbulence, &col);
        result.map_err(|i| self.non_finite("nu_t", i, self.time))
    }

    /// Cell diffusivities and face conductances from `ratio`, `phi` and `nu_t`.
    fn update_coefficients(&mut self) {
        let nu_f = self.params.viscosity;
        for (((k, &r), &phi), &nt) in self.k.iter_mut().zip(&self.ratio).zip(&self.phi).zip(self.eddy.values()) {
            *k = (1.0 - phi) * (nu_f * r + nt);
        }
        self.op.conductances(self.params.density, &self.k, &mut self.cond);
    }

    /// Assemble and solve the backward-Euler system for `dt` (infinite: steady), or the
    /// BDF2 one with step ratio `bdf2` (0: backward Euler; u^{n-1} in `previous`).
    fn solve_linear(&mut self, dt: f64, time: f64, bdf2: Option<f64>) -> Result<(), ColumnError> {
        let n = self.u.len();
        let rho = self.params.density;
        let inv_dt = if dt.is_finite() { 1.0 / dt } else { 0.0 };
        let dz = self.op.grid().dz();
        let t = &mut self.tri;
        for (i, &dzi) in dz.iter().enumerate() {
            let mut tm = (1.0 - self.phi[i]) * rho * dzi * inv_dt;
            let mut old = self.u[i];
            if let Some(w) = bdf2.filter(|&w| w > 0.0) {
                let b = Bdf2::new(w);
                old = b.old(self.u[i], self.previous[i]);
                tm *= b.scale();
            }
            let b = self.beta[i] * dzi;
            t.lower[i] = 0.0;
            t.upper[i] = 0.0;
            t.diag[i] = tm + b;
            t.rhs[i] = tm * old + self.source[i] * dzi + b * self.u_p[i];
        }
        // the side walls: a drag towards u = 0
        for ((d, &g), &dzi) in t.diag.iter_mut().zip(&self.wall).zip(dz) {
            *d += g * dzi;
        }
        self.op.add_diffusion(&self.cond, t);
        // bottom no-slip wall (u_w = 0): flux rho k_0 du/dz
        self.op.add_wall(rho * self.k[0], t);
        if let TopBoundary::Lid { velocity } = self.params.top {
            self.op.add_lid(rho * self.k[n - 1], velocity, t);
        }
        if let Err(row) = t.solve(&mut self.u) {
            return Err(ColumnError::Singular { row, time });
        }
        if let Some(i) = self.u.iter().position(|v| !v.is_finite()) {
            return Err(self.non_finite("u_f", i, time));
        }
        Ok(())
    }

    /// Face velocities, shear rate, stresses and residual from `u` and the coefficients.
    fn update_derived(&mut self) {
        self.update_faces();
        self.update_stresses();
    }

    /// Face velocities and shear rate from `u`.
    fn update_faces(&mut self) {
        let top = match self.params.top {
            TopBoundary::Lid { velocity } => velocity,
            TopBoundary::FreeSurface | TopBoundary::Symmetry => self.op.stress_free_top(&self.u),
        };
        self.op.flux_continuous_faces(&self.k, &self.u, top, &mut self.u_face);
        // the diffusivity does not enter the shear rate, so nu_t feeds back on itself only
        // through the closure
        let shear_top = match self.params.top {
            TopBoundary::Lid { velocity } => velocity,
            TopBoundary::FreeSurface | TopBoundary::Symmetry => self.op.stress_free_shear_top(&self.u),
        };
        self.op.shear_rate(&self.u, shear_top, &mut self.dudz);
    }

    /// Stresses (the discrete fluxes) and the steady residual from `u` and the
    /// coefficients.
    fn update_stresses(&mut self) {
        let n = self.u.len();
        let dz = self.op.grid().dz();
        let u = &self.u;
        let rho = self.params.density;
        self.stress[0] = rho * self.k[0] * self.op.wall_gradient(u);
        for j in 1..n {
            self.stress[j] = self.cond[j] * (u[j] - u[j - 1]);
        }
        self.stress[n] = match self.params.top {
            TopBoundary::Lid { velocity } => rho * self.k[n - 1] * self.op.lid_gradient(u, velocity),
            TopBoundary::FreeSurface | TopBoundary::Symmetry => 0.0,
        };
        // residual of the steady equation
        let mut worst: f64 = 0.0;
        let mut scale = self.stress[0].abs() + self.stress[n].abs();
        for i in 0..n {
            let mut drag = self.beta[i] * (u[i] - self.u_p[i]) * dz[i];
            if let Some(g) = self.wall.get(i) {
                drag += g * u[i] * dz[i];
            }
            let s = self.source[i] * dz[i];
            let r = self.stress[i + 1] - self.stress[i] + s - drag;
            worst = worst.max(r.abs());
            scale += s.abs() + drag.abs();
        }
        self.residual = if worst == 0.0 { 0.0 } else { worst / scale };
    }
}
