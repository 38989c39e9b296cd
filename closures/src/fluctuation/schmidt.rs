//! Gradient diffusion of the suspended phase with a Schmidt number (Chassagne eq 4.4).

use rand_distr::{Distribution, Exp1, StandardNormal};
use saltus_core::closure::Family;
use saltus_core::rng::Rng;
use saltus_core::{
    register_model, Describe, Field, FlowScales, Fluctuation, FluctuationDraw, Limit, Needs, ParticleSlip,
    TurbulencePoint,
};
use serde::{Deserialize, Serialize};

use super::MeanField;
use saltus_core::DriftForm;

/// Turbulent diffusivity of the particles from the eddy viscosity and a Schmidt number
///
/// D = nu_t / Sc, the drift velocity u_d = (nu_t / Sc) grad(phi) / phi of Chassagne et al.
/// 2023 eq 4.4 (Cheng et al. eq 40 with nu_p = nu_ft / Sc).
///
/// * Source: Chassagne, Bonamy & Chauchat 2023 eqs 4.3-4.4 (Sc = 1/3 there); Cheng,
///   Chauchat, Hsu & Calantoni eq 40 and section 4.1 (their EIM gives Sc = 1.5-0.65 in sheet
///   flow, 0.44 measured).
/// * Defaults: `sc = 1/3` (Chassagne eq 4.4), `mean_field = "gradient"` (the flux
///   -D dphi/dz of eq 4.4; `ito` gives -d(D phi)/dz, the diffusion limit of the draws
///   below, see [`MeanField`]).
/// * Valid range: `sc` in (0, 10]. Needs the eddy viscosity (mean-field face) and the
///   Reynolds shear stress (particle face): `mixing_length`, `parabolic` or `k_omega`.
///
/// Particle face (a random walk with the same diffusivity): each component
/// u'_i = sigma N(0, 1), sigma^2 = R_xz/(rho_f eps), held for an exponential time of mean
/// tau = nu_t / (Sc sigma^2) = 1 / (Sc |du/dz|). Exponential holding times make the
/// autocorrelation sigma^2 exp(-s/tau), so Taylor's theorem gives D = sigma^2 tau = nu_t / Sc,
/// the mean-field value, whatever the phase of the first draw.
///
/// Decisions:
/// * Random numbers: three standard normals then one standard exponential, always consumed.
/// * No fluctuation where nu_t or the Reynolds stress is not positive and finite: u' = 0,
///   D = 0, and the draw holds forever (like `drw` without a turnover time); a solver
///   starting from rest should redraw when the flow develops.
/// * Declared limit: D >= 0 (nu_t > 0 and Sc > 0, or D = 0).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "schmidt",
    source = "Chassagne et al. 2023 eqs 4.3-4.4; Cheng et al. eq 40",
    equation = "D = nu_t / Sc; u_i = sqrt(R_xz) N(0,1) held Exp(nu_t/(Sc R_xz))",
    limits = [Limit::NonNegative]
)]
pub struct Schmidt {
    /// Schmidt number Sc = nu_t / D
    #[param(range = "(0, 10]", unit = "-")]
    pub sc: f64,
    /// mean-field form of the drift: `gradient` (Chassagne eq 4.4) or `ito` (the diffusion
    /// limit of this model's draws)
    pub mean_field: MeanField,
}

impl Default for Schmidt {
    fn default() -> Self {
        Self { sc: 1.0 / 3.0, mean_field: MeanField::Gradient }
    }
}

#[typetag::serde(name = "schmidt")]
impl Fluctuation for Schmidt {
    fn needs(&self) -> Needs {
        Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress])
    }

    fn draw(&self, t: &TurbulencePoint, _p: &ParticleSlip, _s: &FlowScales, rng: &mut Rng) -> FluctuationDraw {
        let n: [f64; 3] = [StandardNormal.sample(rng), StandardNormal.sample(rng), StandardNormal.sample(rng)];
        let e: f64 = Exp1.sample(rng);
        let (r, nu) = (t.reynolds_stress, t.nu_t);
        if !(r.is_finite() && r > 0.0 && nu.is_finite() && nu > 0.0) {
            return FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY };
        }
        let s = r.sqrt();
        FluctuationDraw { u: [s * n[0], s * n[1], s * n[2]], duration: e * nu / (self.sc * r) }
    }

    fn drift_form(&self) -> DriftForm {
        self.mean_field.form()
    }

    fn diffusivity(&self, t: &TurbulencePoint, _s: &FlowScales) -> f64 {
        if t.nu_t.is_finite() && t.nu_t > 0.0 {
            t.nu_t / self.sc
        } else {
            0.0
        }
    }
}

register_model!(Family::Fluctuation, "schmidt", Fluctuation, Schmidt);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluctuation::sim::{displacements, mean_se};
    use approx::assert_relative_eq;
    use proptest::prelude::*;
    use saltus_core::rng::Rng;

    fn point() -> TurbulencePoint {
        TurbulencePoint { k: 0.0, omega: 0.0, nu_t: 1e-3, reynolds_stress: 4e-4 }
    }

    #[test]
    fn diffusivity_is_nu_t_over_sc() {
        let m = Schmidt { sc: 0.7, ..Schmidt::default() };
        assert_relative_eq!(m.diffusivity(&point(), &FlowScales::default()), 1e-3 / 0.7, max_relative = 1e-15);
        assert_relative_eq!(
            Schmidt::default().diffusivity(&point(), &FlowScales::default()),
            3e-3,
            max_relative = 1e-15
        );
    }

    #[test]
    fn simulated_diffusivity_matches_mean_field() {
        // 10 000 tracers over t = 100 tau (tau = nu_t/(Sc R) = 2.5 s / Sc): finite-time
        // expectation D (1 - (tau/t)(1 - exp(-t/tau))), relative standard error ~1.4 %;
        // tolerance 4 standard errors.
        let m = Schmidt::default();
        let tp = point();
        let tau = tp.nu_t / (m.sc * tp.reynolds_stress);
        let t_end = 100.0 * tau;
        let s = FlowScales::default();
        let dz = displacements(&m, &tp, &s, 10_000, t_end, 40, &|_: &mut Rng| 1.0);
        let sq: Vec<f64> = dz.iter().map(|z| z * z / (2.0 * t_end)).collect();
        let (est, se) = mean_se(&sq);
        let expected = m.diffusivity(&tp, &s) * (1.0 - tau / t_end * (1.0 - (-t_end / tau).exp()));
        assert!(se < 0.02 * expected);
        assert!((est - expected).abs() < 4.0 * se, "D_sim = {est} +- {se}, D = {expected}");
    }

    #[test]
    fn no_turbulence_no_fluctuation_and_no_nan() {
        let m = Schmidt::default();
        let s = FlowScales::default();
        let mut rng = saltus_core::rng::stream(1, 2);
        for (nu_t, r) in [(0.0, 1e-3), (1e-3, 0.0), (f64::NAN, 1e-3), (1e-3, f64::NAN), (-1.0, 1e-3)] {
            let tp = TurbulencePoint { nu_t, reynolds_stress: r, ..TurbulencePoint::default() };
            let d = m.draw(&tp, &ParticleSlip::default(), &s, &mut rng);
            assert_eq!(d, FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY });
            let dd = m.diffusivity(&tp, &s);
            assert!(dd.is_finite() && dd >= 0.0);
        }
    }

    #[test]
    fn validate_names_the_key() {
        assert_eq!(Schmidt { sc: 0.0, ..Schmidt::default() }.validate().unwrap_err().key, "sc");
        assert_eq!(Schmidt { sc: 11.0, ..Schmidt::default() }.validate().unwrap_err().key, "sc");
        assert!(Schmidt::default().validate().is_ok());
        assert_eq!(Schmidt::default().needs(), Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress]));
    }

    proptest! {
        #[test]
        fn diffusivity_scales_inversely_with_sc(nu in 0.0f64..1.0, sc in 0.01f64..10.0) {
            let tp = TurbulencePoint { nu_t: nu, ..TurbulencePoint::default() };
            let d = Schmidt { sc, ..Schmidt::default() }.diffusivity(&tp, &FlowScales::default());
            prop_assert!(d.is_finite() && d >= 0.0);
            prop_assert!((d * sc - nu).abs() <= 1e-12 * nu.max(1e-300));
        }
    }
}
