//! Two-phase low-Reynolds-number k-omega closure (Cheng, Chauchat, Hsu & Calantoni,
//! section 2.3, eqs 19-35 and table 1).

use saltus_core::closure::turbulence::{TwoEquation, TwoEquationInput, TwoEquationTerms, WallOmega};
use saltus_core::closure::Family;
use saltus_core::{register_model, ColumnView, Describe, Field, Needs, Params, Turbulence};
use serde::{Deserialize, Serialize};

/// Bottom-wall treatment of omega in [`KOmega`].
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum KOmegaWall {
    /// smooth wall, eqs 30-31: omega imposed in the first cell
    #[default]
    Smooth,
    /// rough wall of Wilcox, eqs 34-35 with k_s = `roughness` d: omega imposed at the wall
    Rough,
}

/// Low-Reynolds-number k-omega turbulence closure for two-phase flow
///
/// In the 1D column (only d/dz terms), with eps = 1 - phi, S = du_f/dz, s = rho_p/rho_f:
///
/// ```text
/// dk/dt = eps nu_t S^2 + d/dz[(nu + nu_t/sigma_k) dk/dz] - C_mu* k omega
///         - 2 beta (1 - lambda) phi k / (rho_f eps) + (1/eps) (nu_t/sigma_c) (s - 1) g dphi/dz      (eq 21)
/// domega/dt = C_1w* (omega/k) eps nu_t S^2 + d/dz[(nu + nu_t/sigma_w) domega/dz] - C_2w omega^2
///         - C_3w 2 beta (1 - lambda) phi omega / (rho_f eps)
///         + C_4w (omega/k) (1/eps) (nu_t/sigma_c) (s - 1) g dphi/dz + Gamma(phi) omega_bed / T_relax   (eq 26)
/// nu_t = alpha* k / omega                                                                              (eq 29)
/// ```
///
/// with Re_t = k / (nu omega),
/// C_mu* = C_mu (4/15 + (Re_t/Re_beta)^4) / (1 + (Re_t/Re_beta)^4) (eq 22),
/// C_1w* = C_1w (1/alpha*) (alpha_0 + Re_t/Re_w) / (1 + Re_t/Re_w) (eq 27),
/// alpha* = (alpha*_0 + Re_t/Re_k) / (1 + Re_t/Re_k) (eq 28),
/// lambda = exp(-C_s St), St = t_p / t_l, t_p = rho_p / beta, t_l = C_t / (C_mu omega) (eq 25),
/// beta the drag coefficient of eq 23 (from the solver's drag and hindrance closures);
/// the in-bed omega relaxation Gamma = (tanh(500 (phi - phi_b)) + 1)/2 (eq 32),
/// 1/T_relax = C_2w omega + C_3w 2 beta (1 - lambda) phi / (rho_f eps) - C_4w (buoyancy)/k
/// (eq 33), omega_bed = S_r u*^2 / nu (eq 34) with S_r(k_s^+) of eq 35, k_s = `roughness` d.
/// Wall (eqs 30-31, `wall = "smooth"`): omega in the first cell, a distance z_o from the
/// wall, is sqrt(omega_vis^2 + omega_log^2), omega_vis = 6 nu / (0.075 z_o^2),
/// omega_log = u* / (sqrt(C_mu) kappa z_o); `wall = "rough"`: omega = omega_bed (eq 34) at
/// the wall face. k = 0 at the wall.
///
/// * Source: Cheng et al. (papers/cheng_chauchat_hsu_calantoni_eddy_interaction_sheet_flow)
///   eqs 19-35 and table 1; low-Reynolds functions of Wilcox (1992); rough wall of Wilcox
///   (1988), K_r of eq 35 recalibrated for these low-Reynolds functions (see decisions).
/// * Defaults (table 1): alpha_0 = 1/9, alpha*_0 = 0.024, Re_k = 6, Re_w = 2.95,
///   Re_beta = 8, C_mu = 0.09, sigma_k = sigma_w = 2, C_s = 1, C_1w = 0.52, C_2w = 0.072,
///   C_3w = 0.14, C_4w = 0; text: C_t = 1/6, kappa = 0.41, phi_b = 0.55, k_s = 2.5 d;
///   two calibrated constants (see decisions): C_s = 0.25 (table 1: 1) and K_r = 65 (text:
///   80); sigma_c = 1 (not given in the paper, see decisions); no time average of the
///   relative velocity (eq 24, text: t_0 = 5 s; see decisions).
/// * Valid range: coefficients positive (C_3w, C_4w, C_s non-negative); phi_b in (0, 1);
///   k_s from 1e-3 to 1e3 d (a vanishing k_s makes omega_bed = 40000 nu / k_s^2 overflow).
///   Low-Reynolds wall-bounded flow with the first cell in the viscous sublayer
///   (z_o^+ < ~2) for the smooth wall and well inside it (z_o^+ < ~0.3) for the rough wall,
///   whose k rises from 0 over a few viscous lengths; sheet flow with a bed at phi > phi_b
///   for the in-bed relaxation.
///
/// Decisions:
/// * eq 31 prints omega_log = u*/sqrt(C_mu kappa z_o), which is not a frequency; the log-layer
///   value of Menter & Esch (2001), which Cheng cites, is u*/(sqrt(C_mu) kappa z_o), used here.
/// * The production is tau_ft/rho_f : grad u with tau_ft of eq 20, i.e. eps nu_t S^2 (the eps
///   of eq 20 kept, as printed); nu_t itself carries no eps (the solver applies it once in
///   the momentum equation, as for the mixing-length closures).
/// * beta of eq 23 is the solver's: in the Eulerian solver the drag coefficient of the
///   phases' current relative velocity. Eq 24 averages that relative velocity in time from
///   t_0 (Cheng: t_0 = 5 s) because in a DEM the cell averages of the grains fluctuate, and
///   |U_r| of a fluctuating slip is larger than |<U_r>|: `slip_average_start = t_0` asks the
///   solver for that average (the DEM scenes of Cheng's cases set it; the DEM then takes beta
///   of eq 23 from the time-averaged difference of the cell-mean fluid and grain velocities
///   instead of the grains' exchange coefficient, docs/notes/k_omega_dem_coupling.md). A
///   steady Eulerian column has no slip fluctuation to average out: there the option changes
///   nothing at steady state and the solver keeps the current relative velocity.
/// * sigma_c (turbulent Schmidt number of the buoyancy terms) is not in table 1; 1 by default.
/// * Every term is split into a non-negative source and a non-negative implicit sink rate:
///   a buoyancy term enters the source when it produces and the sink when it destroys;
///   1/T_relax is clamped at 0 (it is positive in sheet flow, the paper's remark after eq 33).
/// * u* of eq 34 is the friction velocity of the forcing at the bed surface, given by the
///   solver; u* of eq 31 is the wall value sqrt((nu + nu_t) |du/dz|), also from the solver.
/// * K_r = 65, not the 80 of the paper (Fuhrman et al. 2010). K_r is the one free constant
///   of the rough wall, fixed by each author so that the model reproduces the rough law of
///   the wall u/u* = ln(z/k_s)/kappa + 8.5: Wilcox (1988) 100 for his high-Reynolds model,
///   Fuhrman et al. 80 for Wilcox (2006). With the low-Reynolds functions of table 1 the wall
///   is smoother (alpha* < 1 where k rises from 0): on a resolved grid (first centre at
///   z+ = 0.1) K_r = 80 puts the log layer of the fixed bed of Revil-Baudard (k_s+ = 390)
///   0.65-0.72 u* above the law, K_r = 65 0.02-0.06 u* above it (the same equations with
///   the damping functions off: K_r = 100 gives -0.27 u*). The same K_r holds for every
///   scene; it only enters omega_bed (rough wall and in-bed relaxation).
/// * C_s = 0.25, not the 1 of table 1. Cheng calibrated C_s "using the sheet flow
///   experimental dataset" of Revil-Baudard et al. (their section 2.3.1) with a DEM sheet;
///   the same calibration on the same data with the continuum sheet of the Eulerian solver,
///   with turbulent suspension on and the bed at the measured packing 0.55 (scenes
///   mobile_bed_*_k_omega.toml), gives 0.25 for both rheologies, the value of SedFoam's
///   1DSheetFlow tutorial for this coefficient (B = 0.25, twophaseRASProperties; B of
///   Cheng et al. 2017a). Without suspension and with beds at 0.59-0.60 the optimum was 0.3.
///   With C_s = 1 the sheet layer laminarises: where k is small, omega is set by the mean
///   shear (omega ~ S at Re_t -> 0), t_l = C_t/(C_mu omega) shrinks, St = t_p/t_l reaches
///   3-5, lambda -> 0.01 and the drag damping (12-18 /s) holds k down; the Reynolds stress in
///   the sheet is 0.03-0.5 u*^2 against 0.9 measured and the surface velocity 1.43 m/s
///   against 0.87. The response is steep (mu(I) scene: C_s = 0.2, 0.25, 0.3, 0.5 give 0.63,
///   0.82, 0.99, 1.27 m/s), docs/notes/k_omega_drag_damping.md. It only acts where phi > 0
///   and the particles do not follow the eddies (St not small).
/// * One value per solver face. 0.25 is the two-fluid model's (the default). The DEM's
///   sheet takes table 1's C_s = 1, Cheng's own calibration with a DEM sheet, with the
///   drag damping's beta from eq 24's time-averaged slip (`slip_average_start`, t_0 =
///   5 s): case MB in the DEM with the eddy-interaction model gives qs* 1.82 (Cheng 1.89)
///   and a surface velocity of 0.88 m/s (data 0.87)
///   (`cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml`,
///   docs/notes/k_omega_dem_coupling.md). Both faces then take beta of the mean slip; why
///   the continuum's sheet needs the weaker damping is not established (its phi profile,
///   without the grains' eddy-driven dispersion, is the untested candidate). A scene that
///   runs both solvers gives the DEM's value in `[solver.lagrangian.closures.turbulence]`.
/// * Initial state: outside the bed the log-layer equilibrium of the forcing (uniform); in
///   the bed (weight Gamma of eq 32) k = 0 and omega = omega_bed, the state the in-bed
///   relaxation of eq 26 and the drag damping of eq 21 lead to (no shear, no production),
///   rather than a bed as turbulent as the flow above it.
/// * No declared limit: its mixing length sqrt(k)/omega comes from the transported k and
///   omega, not from the distance to the wall, so l_m -> kappa z at a wall does not hold by
///   construction (in the viscous sublayer k ~ z^2 and omega ~ 6 nu/(0.075 z^2), l_m ~ z^3;
///   kappa z is only approached in the log layer).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "k_omega",
    source = "Cheng, Chauchat, Hsu & Calantoni eqs 19-35 and table 1 (Wilcox 1992 low-Re k-omega, two-phase terms)",
    equation = "nu_t = alpha* k/omega; dk/dt = eps nu_t S^2 + diff - C_mu* k omega - drag - buoyancy; domega/dt = C_1w* (omega/k) eps nu_t S^2 + diff - C_2w omega^2 - ... + Gamma omega_bed/T_relax"
)]
pub struct KOmega {
    /// alpha_0 of eq 27
    #[param(range = "(0, inf)", unit = "-")]
    pub alpha_0: f64,
    /// alpha*_0 of eq 28
    #[param(range = "(0, inf)", unit = "-")]
    pub alpha_star_0: f64,
    /// Re_k of eq 28
    #[param(range = "(0, inf)", unit = "-")]
    pub re_k: f64,
    /// Re_omega of eq 27
    #[param(range = "(0, inf)", unit = "-")]
    pub re_omega: f64,
    /// Re_beta of eq 22
    #[param(range = "(0, inf)", unit = "-")]
    pub re_beta: f64,
    /// C_mu of eq 22
    #[param(range = "(0, inf)", unit = "-")]
    pub c_mu: f64,
    /// Prandtl number of k
    #[param(range = "(0, inf)", unit = "-")]
    pub sigma_k: f64,
    /// Prandtl number of omega
    #[param(range = "(0, inf)", unit = "-")]
    pub sigma_omega: f64,
    /// C_s of eq 25
    #[param(range = "[0, inf)", unit = "-")]
    pub c_s: f64,
    /// eddy life time coefficient C_t
    #[param(range = "(0, inf)", unit = "-")]
    pub c_t: f64,
    /// C_1omega of eq 27
    #[param(range = "(0, inf)", unit = "-")]
    pub c_1omega: f64,
    /// C_2omega of eq 26
    #[param(range = "(0, inf)", unit = "-")]
    pub c_2omega: f64,
    /// C_3omega of eq 26 (drag)
    #[param(range = "[0, inf)", unit = "-")]
    pub c_3omega: f64,
    /// C_4omega of eq 26 (buoyancy)
    #[param(range = "[0, inf)", unit = "-")]
    pub c_4omega: f64,
    /// turbulent Schmidt number of the buoyancy terms
    #[param(range = "(0, inf)", unit = "-")]
    pub sigma_c: f64,
    /// von Karman constant of eq 31
    #[param(range = "(0, 1]", unit = "-")]
    pub kappa: f64,
    /// bottom-wall treatment
    pub wall: KOmegaWall,
    /// Nikuradse roughness k_s in diameters (eq 35)
    #[param(range = "[1e-3, 1e3]", unit = "d")]
    pub roughness: f64,
    /// K_r of eq 35
    #[param(range = "(0, inf)", unit = "-")]
    pub k_r: f64,
    /// bed volume fraction phi_b of eq 32
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_bed: f64,
    /// start t_0 of the time average of the phases' relative velocity in beta (eq 24); none:
    /// the current relative velocity
    #[serde(skip_serializing_if = "Option::is_none")]
    #[param(range = "[0, inf)", unit = "s")]
    pub slip_average_start: Option<f64>,
}

impl Default for KOmega {
    fn default() -> Self {
        Self {
            alpha_0: 1.0 / 9.0,
            alpha_star_0: 0.024,
            re_k: 6.0,
            re_omega: 2.95,
            re_beta: 8.0,
            c_mu: 0.09,
            sigma_k: 2.0,
            sigma_omega: 2.0,
            c_s: 0.25,
            c_t: 1.0 / 6.0,
            c_1omega: 0.52,
            c_2omega: 0.072,
            c_3omega: 0.14,
            c_4omega: 0.0,
            sigma_c: 1.0,
            kappa: 0.41,
            wall: KOmegaWall::Smooth,
            roughness: 2.5,
            k_r: 65.0,
            phi_bed: 0.55,
            slip_average_start: None,
        }
    }
}

/// Sharpness of the step function of eq 32.
const GAMMA_SHARPNESS: f64 = 500.0;

impl KOmega {
    /// alpha* of eq 28 at turbulent Reynolds number `re_t`.
    #[inline]
    pub fn alpha_star(&self, re_t: f64) -> f64 {
        let r = re_t / self.re_k;
        (self.alpha_star_0 + r) / (1.0 + r)
    }

    /// C_mu* of eq 22.
    #[inline]
    pub fn c_mu_star(&self, re_t: f64) -> f64 {
        let r4 = (re_t / self.re_beta).powi(4);
        if r4.is_infinite() {
            return self.c_mu;
        }
        self.c_mu * (4.0 / 15.0 + r4) / (1.0 + r4)
    }

    /// C_1omega* alpha* (eqs 27-28): the factor of eps S^2 in the omega production, since
    /// (omega/k) nu_t = alpha*.
    #[inline]
    pub fn omega_production_factor(&self, re_t: f64) -> f64 {
        let r = re_t / self.re_omega;
        self.c_1omega * (self.alpha_0 + r) / (1.0 + r)
    }

    /// C_1omega* of eq 27.
    #[inline]
    pub fn c_1omega_star(&self, re_t: f64) -> f64 {
        self.omega_production_factor(re_t) / self.alpha_star(re_t)
    }

    /// Turbulent Reynolds number k / (nu omega).
    #[inline]
    pub fn re_t(k: f64, omega: f64, nu: f64) -> f64 {
        k / (nu * omega)
    }

    /// Eddy viscosity of eq 29.
    #[inline]
    pub fn nu_t(&self, k: f64, omega: f64, nu: f64) -> f64 {
        self.alpha_star(Self::re_t(k, omega, nu)) * k / omega
    }

    /// Turbulence modulation lambda = exp(-C_s St) of eq 25 for the drag coefficient `beta`
    /// of eq 23 (kg m^-3 s^-1), particle density `rho_p` and omega; 1 when beta = 0 is
    /// not reached (beta -> 0 gives St -> inf, lambda -> 0).
    #[inline]
    pub fn lambda(&self, beta: f64, rho_p: f64, omega: f64) -> f64 {
        if beta <= 0.0 {
            return 0.0;
        }
        let st = rho_p / beta * self.c_mu * omega / self.c_t;
        (-self.c_s * st).exp()
    }

    /// Step function Gamma of eq 32.
    #[inline]
    pub fn gamma(&self, phi: f64) -> f64 {
        0.5 * ((GAMMA_SHARPNESS * (phi - self.phi_bed)).tanh() + 1.0)
    }

    /// S_r of eq 35 at roughness Reynolds number k_s^+.
    pub fn s_r(&self, ks_plus: f64) -> f64 {
        let ks = ks_plus.max(1e-300);
        let smooth = (200.0 / ks).powi(2);
        if ks < 5.0 {
            smooth
        } else {
            let rough = self.k_r / ks;
            rough + (smooth - rough) * (5.0 - ks).exp()
        }
    }

    /// omega_bed = S_r u*^2 / nu of eq 34 with k_s = `roughness` d.
    ///
    /// Below k_s^+ = 5 eq 35's S_r = (200 / k_s^+)^2 makes omega_bed = 40000 nu / k_s^2,
    /// independent of u*: written so, a bed without shear (u* = 0, the mean driving of an
    /// oscillatory flow) has the finite omega of the limit instead of 0 x inf.
    pub fn omega_bed(&self, u_star: f64, nu: f64, diameter: f64) -> f64 {
        let ks = self.roughness * diameter;
        let ks_plus = ks * u_star / nu;
        if ks_plus < 5.0 && ks > 0.0 {
            return 40000.0 * nu / (ks * ks);
        }
        self.s_r(ks_plus) * u_star * u_star / nu
    }

    /// Smooth-wall omega of eqs 30-31 at distance `z0` from the wall.
    pub fn omega_smooth_wall(&self, z0: f64, u_star: f64, nu: f64) -> f64 {
        let vis = 6.0 * nu / (0.075 * z0 * z0);
        let log = u_star / (self.c_mu.sqrt() * self.kappa * z0);
        vis.hypot(log)
    }
}

#[typetag::serde(name = "k_omega")]
impl Turbulence for KOmega {
    fn provides(&self) -> Needs {
        Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress, Field::Tke, Field::Omega])
    }

    fn transported(&self) -> &'static [&'static str] {
        &["k", "omega"]
    }

    /// Turbulent length scale sqrt(k)/omega; zero without transported fields.
    fn mixing_length(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        match col.transported {
            [k, w, ..] => {
                for ((o, &k), &w) in out.iter_mut().zip(*k).zip(*w) {
                    *o = k.max(0.0).sqrt() / w;
                }
            }
            _ => out.fill(0.0),
        }
    }

    /// nu_t of eq 29 from the transported k and omega; zero without them.
    fn eddy_viscosity(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        match col.transported {
            [k, w, ..] => {
                for ((o, &k), &w) in out.iter_mut().zip(*k).zip(*w) {
                    *o = self.nu_t(k.max(0.0), w, col.nu_f);
                }
            }
            _ => out.fill(0.0),
        }
    }

    fn as_two_equation(&self) -> Option<&dyn TwoEquation> {
        Some(self)
    }
}

impl TwoEquation for KOmega {
    fn terms(&self, input: &TwoEquationInput<'_>, out: &mut TwoEquationTerms) {
        let col = &input.col;
        let [k, w, ..] = col.transported else {
            return;
        };
        let nu = col.nu_f;
        let rho_f = input.fluid_density;
        let s_m1 = input.particle_density / rho_f - 1.0;
        let omega_bed = self.omega_bed(input.friction_velocity, nu, col.diameter);
        for i in 0..col.len() {
            let phi = col.phi[i].clamp(0.0, 1.0 - 1e-12);
            let eps = 1.0 - phi;
            let (k, w) = (k[i].max(0.0), w[i]);
            let re_t = Self::re_t(k, w, nu);
            let a_star = self.alpha_star(re_t);
            let nu_t = a_star * k / w;
            let s2 = col.dudz[i] * col.dudz[i];
            let beta = input.drag[i];
            let drag_rate = 2.0 * beta * (1.0 - self.lambda(beta, input.particle_density, w)) * phi / (rho_f * eps);
            // buoyancy over nu_t: > 0 produces (unstable), < 0 destroys (stable stratification)
            let b = s_m1 * input.gravity_normal * input.dphidz[i] / (eps * self.sigma_c);
            let buoy_k = nu_t * b;
            out.k_source[i] = eps * nu_t * s2 + buoy_k.max(0.0);
            // (-buoy_k)/k written as alpha* b / omega, finite as k -> 0
            out.k_sink[i] = self.c_mu_star(re_t) * w + drag_rate + (-a_star * b / w).max(0.0);
            out.k_diffusivity[i] = nu + nu_t / self.sigma_k;
            // (omega/k) nu_t = alpha*: the omega buoyancy is C_4w alpha* b, its rate over omega
            // C_4w alpha* b / omega
            let buoy_w = self.c_4omega * a_star * b;
            let sink_w = self.c_2omega * w + self.c_3omega * drag_rate + (-buoy_w / w).max(0.0);
            let inv_relax = (self.c_2omega * w + self.c_3omega * drag_rate - buoy_w / w).max(0.0);
            // outside the bed Gamma underflows to 0; skipping the term there keeps a clear
            // column finite even when omega_bed is not (d = 0 gives k_s+ = 0, S_r = inf)
            let gamma = self.gamma(phi);
            let relax = if gamma > 0.0 { gamma * omega_bed * inv_relax } else { 0.0 };
            out.omega_source[i] = self.omega_production_factor(re_t) * eps * s2 + buoy_w.max(0.0) + relax;
            out.omega_sink[i] = sink_w;
            out.omega_diffusivity[i] = nu + nu_t / self.sigma_omega;
        }
    }

    fn eddy_viscosity_of(&self, k: f64, omega: f64, nu: f64) -> f64 {
        self.nu_t(k, omega, nu)
    }

    fn slip_average_start(&self) -> Option<f64> {
        self.slip_average_start
    }

    fn wall_location(&self) -> WallOmega {
        match self.wall {
            KOmegaWall::Smooth => WallOmega::FirstCell,
            KOmegaWall::Rough => WallOmega::WallFace,
        }
    }

    fn wall_omega(&self, z0: f64, u_star: f64, nu: f64, diameter: f64) -> f64 {
        match self.wall {
            KOmegaWall::Smooth => self.omega_smooth_wall(z0, u_star, nu),
            KOmegaWall::Rough => self.omega_bed(u_star, nu, diameter),
        }
    }

    /// k = u*^2 / sqrt(C_mu) (log-layer equilibrium) and omega = sqrt(k) / (C_mu^(1/4) l)
    /// with l = 0.07 height, floored so that a column without forcing starts from a small
    /// but positive k.
    fn initial_state(&self, u_star: f64, height: f64, nu: f64) -> (f64, f64) {
        let k = (u_star * u_star / self.c_mu.sqrt()).max((nu / height).powi(2));
        let w = k.sqrt() / (self.c_mu.powf(0.25) * 0.07 * height);
        (k, w)
    }

    /// [`TwoEquation::initial_state`] outside the bed; inside it (weight Gamma(phi) of
    /// eq 32) k = 0 and omega = omega_bed of eq 34, the steady state of a bed without shear.
    fn initial_state_at(&self, phi: f64, u_star: f64, height: f64, nu: f64, diameter: f64) -> (f64, f64) {
        let (k, w) = self.initial_state(u_star, height, nu);
        let gamma = self.gamma(phi.clamp(0.0, 1.0));
        if gamma <= 0.0 {
            return (k, w);
        }
        let w_bed = self.omega_bed(u_star, nu, diameter);
        // a column without forcing has no omega_bed (u* = 0): keep its omega
        let w_bed = if w_bed.is_finite() && w_bed > 0.0 { w_bed } else { w };
        ((1.0 - gamma) * k, (1.0 - gamma) * w + gamma * w_bed)
    }
}

register_model!(Family::Turbulence, "k_omega", Turbulence, KOmega);

#[cfg(test)]
mod tests;
