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
///   (1988) with K_r = 80 of Fuhrman et al. (2010).
/// * Defaults (table 1): alpha_0 = 1/9, alpha*_0 = 0.024, Re_k = 6, Re_w = 2.95,
///   Re_beta = 8, C_mu = 0.09, sigma_k = sigma_w = 2, C_s = 1, C_1w = 0.52, C_2w = 0.072,
///   C_3w = 0.14, C_4w = 0; text: C_t = 1/6, kappa = 0.41, phi_b = 0.55, k_s = 2.5 d,
///   K_r = 80; sigma_c = 1 (not given in the paper, see decisions).
/// * Valid range: coefficients positive (C_3w, C_4w, C_s non-negative); phi_b in (0, 1).
///   Low-Reynolds wall-bounded flow with the first cell in the viscous sublayer
///   (z_o^+ < ~2) for the smooth wall; sheet flow with a bed at phi > phi_b for the in-bed
///   relaxation.
///
/// Decisions:
/// * eq 31 prints omega_log = u*/sqrt(C_mu kappa z_o), which is not a frequency; the log-layer
///   value of Menter & Esch (2001), which Cheng cites, is u*/(sqrt(C_mu) kappa z_o), used here.
/// * The production is tau_ft/rho_f : grad u with tau_ft of eq 20, i.e. eps nu_t S^2 (the eps
///   of eq 20 kept, as printed); nu_t itself carries no eps (the solver applies it once in
///   the momentum equation, as for the mixing-length closures).
/// * beta is evaluated with the current slip, not the time average of eq 24 (a steady 1D
///   column has no turbulent slip fluctuation to average out).
/// * sigma_c (turbulent Schmidt number of the buoyancy terms) is not in table 1; 1 by default.
/// * Every term is split into a non-negative source and a non-negative implicit sink rate:
///   a buoyancy term enters the source when it produces and the sink when it destroys;
///   1/T_relax is clamped at 0 (it is positive in sheet flow, the paper's remark after eq 33).
/// * u* of eq 34 is the friction velocity of the forcing at the bed surface, given by the
///   solver; u* of eq 31 is the wall value sqrt((nu + nu_t) |du/dz|), also from the solver.
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
    #[param(range = "(0, inf)", unit = "d")]
    pub roughness: f64,
    /// K_r of eq 35
    #[param(range = "(0, inf)", unit = "-")]
    pub k_r: f64,
    /// bed volume fraction phi_b of eq 32
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_bed: f64,
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
            c_s: 1.0,
            c_t: 1.0 / 6.0,
            c_1omega: 0.52,
            c_2omega: 0.072,
            c_3omega: 0.14,
            c_4omega: 0.0,
            sigma_c: 1.0,
            kappa: 0.41,
            wall: KOmegaWall::Smooth,
            roughness: 2.5,
            k_r: 80.0,
            phi_bed: 0.55,
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
    pub fn omega_bed(&self, u_star: f64, nu: f64, diameter: f64) -> f64 {
        let ks_plus = self.roughness * diameter * u_star / nu;
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
}

register_model!(Family::Turbulence, "k_omega", Turbulence, KOmega);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const NU: f64 = 1e-6;

    fn terms_of(m: &KOmega, cells: &[(f64, f64, f64, f64, f64, f64)]) -> TwoEquationTerms {
        // (phi, dudz, k, omega, beta, dphidz)
        let n = cells.len();
        let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * 1e-3).collect();
        let dz = vec![1e-3; n];
        let phi: Vec<f64> = cells.iter().map(|c| c.0).collect();
        let dudz: Vec<f64> = cells.iter().map(|c| c.1).collect();
        let k: Vec<f64> = cells.iter().map(|c| c.2).collect();
        let w: Vec<f64> = cells.iter().map(|c| c.3).collect();
        let beta: Vec<f64> = cells.iter().map(|c| c.4).collect();
        let dphidz: Vec<f64> = cells.iter().map(|c| c.5).collect();
        let tr = [k.as_slice(), w.as_slice()];
        let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 3e-3, nu_f: NU, transported: &tr };
        let input = TwoEquationInput {
            col,
            drag: &beta,
            dphidz: &dphidz,
            fluid_density: 1000.0,
            particle_density: 1192.0,
            gravity_normal: 9.81,
            friction_velocity: 0.05,
        };
        let mut out = TwoEquationTerms::new(n);
        m.terms(&input, &mut out);
        out
    }

    #[test]
    fn defaults_are_table_1() {
        let m = KOmega::default();
        assert_eq!(
            [m.alpha_0, m.alpha_star_0, m.re_k, m.re_omega, m.re_beta, m.c_mu, m.sigma_k, m.sigma_omega],
            [1.0 / 9.0, 0.024, 6.0, 2.95, 8.0, 0.09, 2.0, 2.0]
        );
        assert_eq!([m.c_s, m.c_1omega, m.c_2omega, m.c_3omega, m.c_4omega], [1.0, 0.52, 0.072, 0.14, 0.0]);
        assert_eq!([m.roughness, m.k_r, m.phi_bed], [2.5, 80.0, 0.55]);
        assert!(m.validate().is_ok());
    }

    #[test]
    fn high_reynolds_limit_is_standard_wilcox() {
        // Re_t -> inf: alpha* -> 1, C_mu* -> C_mu, C_1w* -> C_1w (Cheng after eq 29)
        let m = KOmega::default();
        assert_relative_eq!(m.alpha_star(1e12), 1.0, max_relative = 1e-10);
        assert_relative_eq!(m.c_mu_star(1e12), 0.09, max_relative = 1e-12);
        assert_relative_eq!(m.c_1omega_star(1e12), 0.52, max_relative = 1e-10);
        assert_eq!(m.c_mu_star(f64::INFINITY), 0.09);
    }

    #[test]
    fn low_reynolds_limit() {
        // Re_t -> 0: alpha* -> alpha*_0, C_mu* -> 4/15 C_mu, C_1w* -> C_1w alpha_0 / alpha*_0
        let m = KOmega::default();
        assert_eq!(m.alpha_star(0.0), 0.024);
        assert_relative_eq!(m.c_mu_star(0.0), 0.09 * 4.0 / 15.0, max_relative = 1e-14);
        assert_relative_eq!(m.c_1omega_star(0.0), 0.52 / 9.0 / 0.024, max_relative = 1e-14);
    }

    #[test]
    fn s_r_is_continuous_at_ks_plus_5_and_tends_to_kr_over_ks() {
        let m = KOmega::default();
        assert_relative_eq!(m.s_r(5.0 - 1e-12), 1600.0, max_relative = 1e-9);
        assert_relative_eq!(m.s_r(5.0), 1600.0, max_relative = 1e-12);
        assert_relative_eq!(m.s_r(200.0), 80.0 / 200.0, max_relative = 1e-12);
        // Revil-Baudard: u* = 0.05, d = 3 mm: k_s+ = 375, omega_bed = 80/375 u*^2/nu
        assert_relative_eq!(m.omega_bed(0.05, NU, 3e-3), 80.0 / 375.0 * 2500.0, max_relative = 1e-12);
    }

    #[test]
    fn smooth_wall_blends_viscous_and_log_values() {
        let m = KOmega::default();
        let (z0, u) = (1e-5, 0.03);
        let vis = 6.0 * NU / (0.075 * z0 * z0);
        let log = u / (0.3 * 0.41 * z0);
        assert_relative_eq!(m.omega_smooth_wall(z0, u, NU), (vis * vis + log * log).sqrt(), max_relative = 1e-14);
        // deep in the viscous sublayer the viscous value dominates
        assert_relative_eq!(m.omega_smooth_wall(1e-7, u, NU), 6.0 * NU / (0.075 * 1e-14), max_relative = 1e-3);
    }

    #[test]
    fn clear_fluid_terms_are_wilcox() {
        let m = KOmega::default();
        let (k, w, g) = (1e-3, 10.0, 5.0);
        let t = terms_of(&m, &[(0.0, g, k, w, 0.0, 0.0)]);
        let re_t = k / (NU * w);
        let nut = m.alpha_star(re_t) * k / w;
        assert_relative_eq!(t.k_source[0], nut * g * g, max_relative = 1e-14);
        assert_relative_eq!(t.k_sink[0], m.c_mu_star(re_t) * w, max_relative = 1e-14);
        assert_relative_eq!(t.omega_source[0], m.c_1omega_star(re_t) * w / k * nut * g * g, max_relative = 1e-12);
        assert_relative_eq!(t.omega_sink[0], 0.072 * w, max_relative = 1e-14);
        assert_relative_eq!(t.k_diffusivity[0], NU + nut / 2.0, max_relative = 1e-14);
    }

    #[test]
    fn in_bed_relaxation_drives_omega_to_omega_bed() {
        // no shear, no drag, no gradient, inside the bed: the local balance
        // source = sink omega gives omega = omega_bed Gamma
        let m = KOmega::default();
        let w = 3.0;
        let t = terms_of(&m, &[(0.6, 0.0, 1e-6, w, 0.0, 0.0)]);
        let steady = t.omega_source[0] / t.omega_sink[0];
        assert_relative_eq!(steady, m.omega_bed(0.05, NU, 3e-3) * m.gamma(0.6), max_relative = 1e-12);
        assert!(m.gamma(0.6) > 1.0 - 1e-10 && m.gamma(0.0) < 1e-100);
    }

    #[test]
    fn stable_stratification_is_a_sink_of_k() {
        let m = KOmega::default();
        let a = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, 0.0)]);
        let b = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, -10.0)]);
        assert_eq!(a.k_source[0], b.k_source[0]);
        assert!(b.k_sink[0] > a.k_sink[0]);
        let c = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, 10.0)]);
        assert!(c.k_source[0] > a.k_source[0]);
        assert_eq!(c.k_sink[0], a.k_sink[0]);
    }

    #[test]
    fn round_trip_and_unknown_keys() {
        let m: KOmega = toml::from_str("wall = \"rough\"\nc_3omega = 0.2").unwrap();
        assert_eq!(m.wall, KOmegaWall::Rough);
        assert_eq!(m.c_3omega, 0.2);
        assert!(toml::from_str::<KOmega>("c3 = 0.2").is_err());
        let bad = KOmega { sigma_k: 0.0, ..KOmega::default() };
        assert_eq!(bad.validate().unwrap_err().key, "sigma_k");
        let bad = KOmega { phi_bed: 1.0, ..KOmega::default() };
        assert_eq!(bad.validate().unwrap_err().key, "phi_bed");
    }

    #[test]
    fn provides_and_transports_k_and_omega() {
        let m = KOmega::default();
        let p = m.provides();
        assert!(p.contains(Field::Tke) && p.contains(Field::Omega) && p.contains(Field::ReynoldsStress));
        assert_eq!(m.transported(), &["k", "omega"]);
        assert!(m.as_two_equation().is_some());
    }

    proptest! {
        #[test]
        fn damping_functions_are_bounded_and_monotone(a in 0.0f64..1e6, b in 0.0f64..1e6) {
            let m = KOmega::default();
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            prop_assert!(m.alpha_star(lo) <= m.alpha_star(hi) + 1e-15);
            prop_assert!(m.alpha_star(hi) >= 0.024 && m.alpha_star(hi) <= 1.0);
            prop_assert!(m.c_mu_star(lo) <= m.c_mu_star(hi) + 1e-15);
            prop_assert!(m.c_mu_star(hi) >= 0.024 - 1e-15 && m.c_mu_star(hi) <= 0.09 + 1e-15);
            prop_assert!(m.omega_production_factor(hi) >= 0.52 / 9.0 - 1e-15);
            prop_assert!(m.omega_production_factor(hi) <= 0.52 + 1e-15);
        }

        #[test]
        fn lambda_in_unit_interval_and_decreasing_in_response_time(
            beta in 1e-3f64..1e8, omega in 1e-3f64..1e5,
        ) {
            let m = KOmega::default();
            let l = m.lambda(beta, 1192.0, omega);
            prop_assert!((0.0..=1.0).contains(&l));
            // heavier drag = shorter response time = particles follow the eddies better
            prop_assert!(m.lambda(2.0 * beta, 1192.0, omega) >= l);
        }

        #[test]
        fn terms_are_non_negative_and_finite(
            cells in proptest::collection::vec(
                (0.0f64..0.64, -100.0f64..100.0, 0.0f64..1.0, 1e-3f64..1e6, 0.0f64..1e6, -500.0f64..500.0),
                1..40,
            ),
            c4 in 0.0f64..1.0,
        ) {
            let m = KOmega { c_4omega: c4, ..KOmega::default() };
            let t = terms_of(&m, &cells);
            for v in [&t.k_source, &t.k_sink, &t.k_diffusivity, &t.omega_source, &t.omega_sink, &t.omega_diffusivity] {
                for x in v.iter() {
                    prop_assert!(x.is_finite() && *x >= 0.0, "{x}");
                }
            }
            for (d, _) in t.k_diffusivity.iter().zip(&cells) {
                prop_assert!(*d >= NU);
            }
        }

        #[test]
        fn eddy_viscosity_batch_is_eq_29(
            cells in proptest::collection::vec((0.0f64..1.0, 1e-3f64..1e4), 1..50),
        ) {
            let m = KOmega::default();
            let n = cells.len();
            let k: Vec<f64> = cells.iter().map(|c| c.0).collect();
            let w: Vec<f64> = cells.iter().map(|c| c.1).collect();
            let z = vec![0.0; n];
            let tr = [k.as_slice(), w.as_slice()];
            let col = ColumnView { z: &z, dz: &z, phi: &z, dudz: &z, diameter: 1e-3, nu_f: NU, transported: &tr };
            let mut out = vec![0.0; n];
            m.eddy_viscosity(&col, &mut out);
            for i in 0..n {
                let re = k[i] / (NU * w[i]);
                let a = (0.024 + re / 6.0) / (1.0 + re / 6.0);
                prop_assert!((out[i] - a * k[i] / w[i]).abs() <= 1e-12 * out[i].abs().max(1e-300));
                prop_assert!(out[i] <= k[i] / w[i] * (1.0 + 1e-12));
            }
        }
    }
}
