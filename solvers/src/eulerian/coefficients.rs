//! Everything the Eulerian step recomputes from the state: shear rates, the drag of the
//! drag kernel, the fluid diffusivities and conductances, the eddy viscosity, the drift
//! diffusivity and (in [`super::stress`]) the particle pressure and stress, with the
//! scratch space of the solves. One batch call per closure family per evaluation.

use saltus_core::{ColumnView, KineticCoefficients, LocalState, SaltationInput, TurbulencePoint};

use super::block::BlockTridiagonal;
use super::config::Top;
use super::rheology::Pressure;
use super::Eulerian;
use crate::column::Tridiagonal;
use crate::inputs::{self, DragPoints};
use crate::run::Breakdown;

/// Coefficients of one evaluation of the column at the current state.
pub(super) struct Coefficients {
    /// shear rates of u_f and u_p per cell, and of u_p at the faces (1/s)
    pub gamma_f: Vec<f64>,
    pub gamma_p: Vec<f64>,
    pub face_gamma: Vec<f64>,
    /// K of eq 2.10 (kg m^-3 s^-1) and beta = phi eps K
    pub k_drag: Vec<f64>,
    pub beta: Vec<f64>,
    /// 1 + d ln C / d ln Re (ux / slip)^2: the tangent of the streamwise drag
    pub drag_tangent: Vec<f64>,
    /// 1 + d ln C / d ln Re (w_r / slip)^2: the tangent of the wall-normal drag, with which
    /// the phi step linearises the settling velocity (see `solve_phi`)
    pub normal_tangent: Vec<f64>,
    /// C_D^inf / C_D(Re*) for the quadratic drag dissipation (eq 3.13)
    pub cd_ratio: Vec<f64>,
    /// eps^2 / C, the wall-normal mobility of the volume-fraction flux
    pub mobility: Vec<f64>,
    /// particle pressure per cell, linearised in phi
    pub pres: Vec<Pressure>,
    /// kinetic theory: dp_el/dphi per cell (Pa)
    pub elastic_slope: Vec<f64>,
    /// local rheologies: weight of the grains above a blocked face, added to the pressure
    /// of the cells below it (Pa)
    pub overburden: Vec<f64>,
    /// nu_eff / nu_f per cell
    pub visc_ratio: Vec<f64>,
    /// drift diffusivity of the fluctuation closure per cell (m^2/s)
    pub drift: Vec<f64>,
    /// kinetic coefficients per cell, dF1/dphi, eta and kappa of the kinetic theory
    pub coef: Vec<KineticCoefficients>,
    pub f1_slope: Vec<f64>,
    pub eta_kin: Vec<f64>,
    pub kappa: Vec<f64>,
    /// particle stress at faces: tau = eta_face gamma + sigma_face, and its value
    pub eta_face: Vec<f64>,
    pub sigma_face: Vec<f64>,
    pub tau_p: Vec<f64>,
    /// eps (nu_eff + nu_t) per cell (m^2/s) and rho_f times its face conductance
    pub fluid_k: Vec<f64>,
    pub fluid_cond: Vec<f64>,
    /// eta_face / h at the interior faces: the particle conductance
    pub part_cond: Vec<f64>,
}

/// Work space of the evaluation and the solves, never read across steps.
pub(super) struct Scratch {
    pub work: Vec<f64>,
    /// face coefficients (c_L, c_R, s) of the volume-fraction fluxes
    pub face_coeffs: Vec<f64>,
    /// drift coefficients (d_L, d_R) of the faces: drift flux (d_L phi_L - d_R phi_R) / h
    pub drift_lr: Vec<f64>,
    pub block: BlockTridiagonal,
    pub xb: Vec<[f64; 2]>,
    pub tri: Tridiagonal,
    /// drag kernel points at Re and at Re (1 + DRE) for the tangent
    pub phi_c: Vec<f64>,
    pub re: Vec<f64>,
    pub re2: Vec<f64>,
    pub drag: DragPoints,
    pub drag2: DragPoints,
    /// inputs of the fluctuation and kinetic closures
    pub turbulence: Vec<TurbulencePoint>,
    pub salt: Vec<SaltationInput>,
    /// phi + dphi and F1 there, for dF1/dphi
    pub phi_h: Vec<f64>,
    pub f1_h: Vec<f64>,
    /// shear rate of the new u_f for k and omega
    pub shear: Vec<f64>,
    /// C_D per cell and the drag-dissipation factor c_J of the temperature step
    pub cd: Vec<f64>,
    pub c_j: Vec<f64>,
    /// local rheologies: states, control numbers and pressures of the cells (at phi and
    /// phi + dphi) and of the faces
    pub cell_states: Vec<LocalState>,
    pub cell_x: Vec<f64>,
    pub cell_x_h: Vec<f64>,
    pub cell_p: Vec<f64>,
    pub cell_p_h: Vec<f64>,
    pub face_states: Vec<LocalState>,
    pub face_p: Vec<f64>,
    pub face_x: Vec<f64>,
    pub face_mu: Vec<f64>,
    pub face_packing: Vec<f64>,
}

/// Relative step of the batch difference of the drag kernel in Re.
const DRE: f64 = 1e-6;

impl Coefficients {
    pub fn new(n: usize) -> Self {
        let v = |x: f64| vec![x; n];
        let f = || vec![0.0; n + 1];
        Self {
            gamma_f: v(0.0),
            gamma_p: v(0.0),
            face_gamma: f(),
            k_drag: v(0.0),
            beta: v(0.0),
            drag_tangent: v(1.0),
            normal_tangent: v(1.0),
            cd_ratio: v(0.0),
            mobility: v(0.0),
            pres: vec![Pressure::default(); n],
            elastic_slope: v(0.0),
            overburden: v(0.0),
            visc_ratio: v(1.0),
            drift: v(0.0),
            coef: vec![KineticCoefficients::default(); n],
            f1_slope: v(0.0),
            eta_kin: v(0.0),
            kappa: v(0.0),
            eta_face: f(),
            sigma_face: f(),
            tau_p: f(),
            fluid_k: v(0.0),
            fluid_cond: f(),
            part_cond: f(),
        }
    }
}

impl Scratch {
    pub fn new(n: usize) -> Self {
        let salt = SaltationInput { sqrt_t: 0.0, k_drag: 0.0, particle_density: 0.0, diameter: 0.0 };
        let state =
            LocalState { shear_rate: 0.0, pressure: 0.0, diameter: 0.0, particle_density: 0.0, fluid_viscosity: 0.0 };
        Self {
            work: vec![0.0; n],
            face_coeffs: vec![0.0; 3 * (n + 1)],
            drift_lr: vec![0.0; 2 * (n + 1)],
            block: BlockTridiagonal::new(n),
            xb: vec![[0.0; 2]; n],
            tri: Tridiagonal::new(n),
            phi_c: vec![0.0; n],
            re: vec![0.0; n],
            re2: vec![0.0; n],
            drag: DragPoints::new(n),
            drag2: DragPoints::new(n),
            turbulence: vec![TurbulencePoint::default(); n],
            salt: vec![salt; n],
            phi_h: vec![0.0; n],
            f1_h: vec![0.0; n],
            shear: vec![0.0; n],
            cd: vec![0.0; n],
            c_j: vec![0.0; n],
            cell_states: vec![state; n],
            cell_x: vec![0.0; n],
            cell_x_h: vec![0.0; n],
            cell_p: vec![0.0; n],
            cell_p_h: vec![0.0; n],
            face_states: vec![state; n + 1],
            face_p: vec![0.0; n + 1],
            face_x: vec![0.0; n + 1],
            face_mu: vec![0.0; n + 1],
            face_packing: vec![0.0; n + 1],
        }
    }
}

impl Eulerian<'_> {
    /// Top value of the fluid velocity in the shear rate: the lid's, or that of a
    /// stress-free top ([`crate::column::ColumnOperator::stress_free_shear_top`]).
    pub(super) fn fluid_top(&self, u: &[f64]) -> f64 {
        match self.cfg.domain.top {
            Top::Lid => self.cfg.domain.lid_velocity,
            _ => self.op.stress_free_shear_top(u),
        }
    }

    /// Shear rates at cells and faces of the current u_f and u_p.
    pub(super) fn shear_rates(&mut self) {
        let top_f = self.fluid_top(&self.s.uf);
        let top_p = self.op.stress_free_shear_top(&self.s.up);
        self.op.shear_rate(&self.s.uf, top_f, &mut self.co.gamma_f);
        self.op.shear_rate(&self.s.up, top_p, &mut self.co.gamma_p);
        self.op.face_gradient(&self.s.up, &mut self.co.face_gamma);
    }

    /// Every coefficient of the step from the current state; the eddy viscosity (state,
    /// lagged) takes its relaxed update here, once per evaluation.
    pub(super) fn evaluate(&mut self) -> Result<(), Breakdown> {
        self.shear_rates();
        self.evaluate_drag();
        let c = self.c;
        self.m.viscosity.ratio_batch(&self.s.phi, &mut self.co.visc_ratio);
        let kw_fields = self.s.kw.as_ref().map(|kw| kw.col.fields());
        let transported: &[&[f64]] = kw_fields.as_ref().map_or(&[], |f| f.as_slice());
        let col = ColumnView {
            z: self.op.grid().centres(),
            dz: self.op.grid().dz(),
            phi: &self.s.phi,
            dudz: &self.co.gamma_f,
            diameter: c.d,
            nu_f: c.nu_f,
            transported,
        };
        let first = self.s.steps == 0;
        if let Err(i) = self.s.eddy.evaluate(self.m.turbulence, &col) {
            return Err(self.breakdown(i, "nu_t", f64::NAN, "eddy viscosity not finite or negative".into()));
        }
        self.s.eddy.relax(first);
        let nu_t = self.s.eddy.values();
        for (i, &nt) in nu_t.iter().enumerate() {
            let eps = 1.0 - self.s.phi[i].max(0.0);
            self.co.fluid_k[i] = eps * (c.nu_f * self.co.visc_ratio[i] + nt);
        }
        self.op.conductances(c.rho_f, &self.co.fluid_k, &mut self.co.fluid_cond);
        self.evaluate_drift();
        self.evaluate_stress();
        Ok(())
    }

    /// K of eq 2.10 from the drag kernel with the full slip magnitude (streamwise and
    /// wall-normal), with the tangent of the streamwise drag from one batch difference.
    fn evaluate_drag(&mut self) {
        let n = self.len();
        let c = self.c;
        let sc = &mut self.sc;
        for i in 0..n {
            let phi = self.s.phi[i].clamp(0.0, 1.0 - 1e-12);
            // the slip of eq 4.3, u_f - u_p + u_d: the particle flux less its drift part
            let f =
                0.5 * (self.s.flux[i] + self.s.flux[i + 1]) - 0.5 * (self.s.drift_flux[i] + self.s.drift_flux[i + 1]);
            let wp = if phi > self.slip_phi { f / phi } else { 0.0 };
            let slip = crate::inputs::mean_slip(self.s.uf[i], self.s.up[i], wp, phi);
            sc.phi_c[i] = phi;
            sc.work[i] = slip;
            sc.re[i] = slip * c.d / c.nu_f;
            sc.re2[i] = sc.re[i] * (1.0 + DRE);
        }
        self.kernel.evaluate(&sc.phi_c, &sc.re, &mut sc.drag);
        self.kernel.evaluate_at_reynolds(&sc.drag, &sc.phi_c, &sc.re2, &mut sc.drag2);
        let stokes = 0.75 * c.rho_f * c.nu_f / (c.d * c.d);
        let cd_inf = self.m.drag.cd_inf();
        let co = &mut self.co;
        for i in 0..n {
            let phi = sc.phi_c[i];
            let eps = 1.0 - phi;
            let re = sc.re[i];
            let (re_h, cdre, fh) = (sc.drag.re_star[i], sc.drag.cd_re[i], sc.drag.factor[i]);
            // C_D(Re*) |u_r| = cd_re(Re*) nu / d / c(phi): finite as Re -> 0
            let conv = 1.0 / self.kernel.reynolds_ratio(phi);
            // C = phi eps K / phi (kg m^-3 s^-1): beta = phi C, K = C / eps
            let cc = stokes * fh * cdre * conv;
            // d ln C / d ln Re for the Newton linearisation of the streamwise drag: a Picard
            // lag of a quadratic drag (slip <- F / (c slip)) oscillates without damping
            let slope = if re > 1e-12 {
                let c2 = sc.drag2.factor[i] * sc.drag2.cd_re[i];
                ((c2 / (fh * cdre)).ln() / (1.0 + DRE).ln()).max(0.0)
            } else {
                0.0
            };
            let ux = self.s.uf[i] - self.s.up[i];
            let slip = sc.work[i];
            // the ratio before the square: ux^2 and slip^2 underflow to 0 (0/0) for a slip
            // below 1e-154 m/s, as the first implicit step of a lid-driven column leaves
            // deep under a fine grid (Couette at 133 cells and more)
            let along = if slip > 0.0 { (ux / slip).powi(2) } else { 0.0 };
            co.drag_tangent[i] = 1.0 + slope * along;
            // (w_r / slip)^2 = 1 - (ux / slip)^2: the slip is the hypotenuse of the two
            co.normal_tangent[i] = 1.0 + if slip > 0.0 { slope * (1.0 - along).max(0.0) } else { 0.0 };
            co.beta[i] = phi * cc;
            co.k_drag[i] = cc / eps;
            co.mobility[i] = eps * eps / cc;
            co.cd_ratio[i] = if cdre > 0.0 { cd_inf * re_h / cdre } else { 0.0 };
        }
    }

    /// Drift diffusivity of the fluctuation closure (Chassagne eqs 4.3-4.4) with the flow
    /// scales and Reynolds stress of [`crate::inputs`], damped by the open fraction
    /// (1 - phi/phi_max) of the cell.
    ///
    /// Why the damping: the drift velocity is the drag of the fluid fluctuations seen by the
    /// grains (eq 4.3); grains in enduring contact do not follow the eddies, the contact
    /// network carries that drag. (1 - phi/phi_max) is the factor by which the Li & Sawamoto
    /// mixing length (Chassagne eq 2.8b, Maurin eq 5) damps the eddies inside a bed: it is
    /// 1 to within phi/phi_max in a dilute suspension (1e-3 in Cheng's dilute cases, so the
    /// Rouse balance is untouched) and vanishes at the packing of the granular closure, so
    /// that no eddy diffusivity of a turbulence closure (k-omega's start-up puts
    /// nu_t = 0.15 m^2/s into a packed bed) can dissolve a packed bed.
    fn evaluate_drift(&mut self) {
        let Some(fl) = self.m.fluctuation else { return };
        let g = self.op.grid();
        let bed = inputs::bed_surface(g.centres(), &self.s.phi, self.cfg.domain.bed_height);
        let scales = inputs::flow_scales(g.centres(), g.dz(), &self.s.uf, g.height(), bed);
        let nu_t = self.s.eddy.values();
        for (i, &nt) in nu_t.iter().enumerate() {
            let (k, omega) = self.s.kw.as_ref().map_or((0.0, 0.0), |kw| (kw.col.k[i], kw.col.omega[i]));
            let reynolds_stress = inputs::reynolds_stress(nt, self.co.gamma_f[i]);
            self.sc.turbulence[i] = TurbulencePoint { k, omega, nu_t: nt, reynolds_stress };
        }
        fl.diffusivity_batch(&self.sc.turbulence, &scales, &mut self.co.drift);
        let phi_max = self.m.rheology.phi_max();
        for (d, &phi) in self.co.drift.iter_mut().zip(&self.s.phi) {
            *d = d.max(0.0) * (1.0 - phi / phi_max).clamp(0.0, 1.0);
        }
    }
}
