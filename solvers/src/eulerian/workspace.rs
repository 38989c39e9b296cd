//! The storage of what the Eulerian step recomputes from the state (the coefficients of
//! one evaluation) and the scratch space of the solves, allocated once for a column; the
//! evaluation itself is [`super::coefficients`].

use saltus_core::{KineticCoefficients, LocalState, SaltationInput, TurbulencePoint};

use super::block::BlockTridiagonal;
use super::rheology::Pressure;
use crate::column::Tridiagonal;
use crate::inputs::DragPoints;

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
    /// the old phi of a volume-fraction step (the BDF2 combination, or the state's phi)
    pub old_phi: Vec<f64>,
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
            old_phi: vec![0.0; n],
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
