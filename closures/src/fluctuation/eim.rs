//! Eddy interaction model of Cheng et al. (CFDEM-EIM, sheet flow).

use rand_distr::{Distribution, Exp1, StandardNormal};
use saltus_core::closure::Family;
use saltus_core::rng::Rng;
use saltus_core::{
    register_model, Describe, Field, FlowScales, Fluctuation, FluctuationDraw, Limit, Needs, ParticleSlip,
    TurbulencePoint,
};
use serde::{Deserialize, Serialize};

use super::{DragReynoldsNumber, MeanField};
use saltus_core::DriftForm;

/// Eddy interaction model (EIM) driven by a k-omega closure
///
/// u'_i = sqrt(2k/3) sigma_i, sigma_i ~ N(0, 1) independent (i = x, y, z), so
/// <u'_i u'_i> = 2k; held for t_I = min(t_e, t_c) with
/// T_l = 1 / (6 C_mu omega), t_e = -C0 ln(1 - xi) T_l, l_e = t_e sqrt(2k/3),
/// t_c = -t_p ln(1 - l_e / (|v - u_f| t_p)) (only when l_e < |v - u_f| t_p; else t_I = t_e).
///
/// * Source: Cheng, Chauchat, Hsu & Calantoni, section 2.4, eqs 36-37 (C_t = 1/6 of the
///   eddy life time, section 2.3; C_mu from their table 1).
/// * Defaults: `c0 = 3` (Cheng's calibration on dilute suspension, confirmed on sheet
///   flow), `c_mu = 0.09` (table 1), `mean_field = "gradient"` (see [`MeanField`]),
///   `drag_reynolds = "instantaneous"` (the DEM drag's Re_p of the slip with u'; `"mean"`
///   takes Cheng's eq 7, the slip without u': [`DragReynoldsNumber`]).
/// * Valid range: `c0` in (0, 20], `c_mu` in (0, 1]. Needs k and omega from the turbulence
///   closure (refused with `mixing_length` or `laminar`).
///
/// Mean-field diffusivity (tracer limit, no crossing-trajectory effect). With zero slip the
/// velocity is held for exponentially distributed times of mean tau = C0 T_l and redrawn
/// independently. Redraws form a Poisson process (memoryless), so u'_z(t) and u'_z(t + s)
/// are equal with probability exp(-s/tau) and independent otherwise:
/// R(s) = (2k/3) exp(-s/tau), Lagrangian integral time tau, and Taylor's theorem gives
///
/// D = (2k/3) C0 T_l = C0 k / (9 C_mu omega).
///
/// Over a finite time t, <dz^2>/(2t) = D (1 - (tau/t)(1 - exp(-t/tau))). With the k-omega
/// eddy viscosity nu_t = k/omega (Cheng eq 29 with alpha* = 1), the Schmidt number is
/// Sc = nu_t / D = 9 C_mu / C0 = 0.27 for the defaults (Chassagne et al. 2023 use
/// Sc = 1/3 in their drift velocity, eq 4.4). Eddy crossing (t_c < t_e) and particle
/// inertia lower the particle diffusivity below this value: Cheng's sheet-flow runs
/// (figure 8c) give Sc = 1.5, 1, 0.75, 0.65 for C0 = 2, 3, 6, 8.
///
/// Mean-field form ([`MeanField`]): the draws hold a velocity of variance 2k/3 and a
/// lifetime of mean C0 T_l both set where the eddy is drawn, so their diffusion limit is
/// the flux -d(D phi)/dz (`ito`), not -D dphi/dz (`gradient`, Chassagne eq 4.4, the
/// default): a particle leaves a strongly turbulent region faster than it enters it, and
/// collects where D is small (near a wall). In Cheng's dilute channel (k-omega, C0 = 3) the
/// two forms give Rouse numbers of about 1.06 and 0.58 (docs/notes/kiger_pan_rouse_number.md).
///
/// Decisions:
/// * Random numbers: three standard normals (x, y, z) then one standard exponential E
///   (t_e = C0 T_l E, the same distribution as -C0 ln(1 - xi) T_l), always consumed, so
///   the same stream gives the same velocities whatever the slip.
/// * omega <= 0 or non-finite: no time scale, so no fluctuation: u' = 0, duration = inf,
///   D = 0.
/// * k <= 0 or non-finite (with a valid omega): u' = 0 held for the eddy lifetime t_e (no
///   crossing, whose time would be 0 for a zero-size eddy), so the particle redraws once
///   the flow turns turbulent; D = 0.
/// * Crossing needs slip > 0; a non-finite response time uses the limit t_c = l_e / slip.
/// * Declared limit: D >= 0 (k > 0, omega > 0 and C0, C_mu positive, or D = 0).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "eim",
    source = "Cheng, Chauchat, Hsu & Calantoni, section 2.4, eqs 36-37, table 1",
    equation = "u_i = sqrt(2k/3) N(0,1), t = min(-C0 ln(1-xi)/(6 C_mu omega), -t_p ln(1 - l_e/(slip t_p))); D = C0 k/(9 C_mu omega)",
    limits = [Limit::NonNegative]
)]
pub struct EddyInteraction {
    /// eddy lifetime coefficient C0
    #[param(range = "(0, 20]", unit = "-")]
    pub c0: f64,
    /// k-omega coefficient C_mu
    #[param(range = "(0, 1]", unit = "-")]
    pub c_mu: f64,
    /// mean-field form of the drift: `ito` (the draws' diffusion limit) or `gradient`
    pub mean_field: MeanField,
    /// the DEM drag's particle Reynolds number: of the slip with u' (`instantaneous`) or
    /// without it (`mean`, Cheng eq 7)
    #[serde(skip_serializing_if = "DragReynoldsNumber::is_instantaneous")]
    pub drag_reynolds: DragReynoldsNumber,
}

impl Default for EddyInteraction {
    fn default() -> Self {
        Self { c0: 3.0, c_mu: 0.09, mean_field: MeanField::Gradient, drag_reynolds: DragReynoldsNumber::Instantaneous }
    }
}

impl EddyInteraction {
    /// Lagrangian time T_l = 1 / (6 C_mu omega); `None` unless omega is positive and finite.
    pub fn lagrangian_time(&self, omega: f64) -> Option<f64> {
        let tl = 1.0 / (6.0 * self.c_mu * omega);
        (omega.is_finite() && omega > 0.0 && tl.is_finite()).then_some(tl)
    }

    /// Eddy crossing time t_c (eq 37) for an eddy of size `l_e`; `None` when the particle
    /// does not cross it (l_e >= slip t_p, or no slip).
    pub fn crossing_time(l_e: f64, p: &ParticleSlip) -> Option<f64> {
        let (slip, tp) = (p.slip, p.response_time);
        if !(slip.is_finite() && slip > 0.0 && tp > 0.0 && l_e.is_finite()) {
            return None;
        }
        if tp.is_infinite() {
            return Some(l_e / slip);
        }
        let reach = slip * tp;
        (l_e < reach).then(|| -tp * (-l_e / reach).ln_1p())
    }
}

#[typetag::serde(name = "eim")]
impl Fluctuation for EddyInteraction {
    fn needs(&self) -> Needs {
        Needs::of(&[Field::Tke, Field::Omega])
    }

    fn draw(&self, t: &TurbulencePoint, p: &ParticleSlip, _s: &FlowScales, rng: &mut Rng) -> FluctuationDraw {
        let n: [f64; 3] = [StandardNormal.sample(rng), StandardNormal.sample(rng), StandardNormal.sample(rng)];
        let e: f64 = Exp1.sample(rng);
        let Some(tl) = self.lagrangian_time(t.omega) else {
            return FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY };
        };
        let t_e = self.c0 * tl * e;
        if !(t.k.is_finite() && t.k > 0.0) {
            return FluctuationDraw { u: [0.0; 3], duration: t_e };
        }
        let s = (2.0 * t.k / 3.0).sqrt();
        let l_e = t_e * s;
        let duration = Self::crossing_time(l_e, p).map_or(t_e, |t_c| t_c.min(t_e));
        FluctuationDraw { u: [s * n[0], s * n[1], s * n[2]], duration }
    }

    fn drift_form(&self) -> DriftForm {
        self.mean_field.form()
    }

    fn drag_reynolds(&self) -> saltus_core::SlipReynolds {
        self.drag_reynolds.form()
    }

    fn diffusivity(&self, t: &TurbulencePoint, _s: &FlowScales) -> f64 {
        match self.lagrangian_time(t.omega) {
            Some(tl) if t.k.is_finite() && t.k > 0.0 => 2.0 * t.k / 3.0 * self.c0 * tl,
            _ => 0.0,
        }
    }
}

register_model!(Family::Fluctuation, "eim", Fluctuation, EddyInteraction);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluctuation::sim::{displacements, mean_se};
    use approx::assert_relative_eq;
    use proptest::prelude::*;
    use saltus_core::rng::{stream, Rng};

    const K: f64 = 0.01;
    const OMEGA: f64 = 10.0;

    fn point() -> TurbulencePoint {
        TurbulencePoint { k: K, omega: OMEGA, nu_t: K / OMEGA, reynolds_stress: 0.0 }
    }
    fn no_slip() -> ParticleSlip {
        ParticleSlip::default()
    }
    fn lifetime_mean() -> f64 {
        3.0 / (6.0 * 0.09 * OMEGA)
    }

    #[test]
    fn components_independent_with_variance_two_thirds_k() {
        // N = 200 000 draws, fixed seed, s^2 = 2k/3. Standard errors: component variance
        // s^2 sqrt(2/N); cross moment s^2 sqrt(1/N); <u_i u_i> (sum of three independent
        // chi^2) s^2 sqrt(6/N); means s sqrt(1/N). Tolerance: 4 standard errors.
        let m = EddyInteraction::default();
        let n = 200_000;
        let nf = n as f64;
        let s2 = 2.0 * K / 3.0;
        let mut rng = stream(2019, 0);
        let mut sum = [0.0; 3];
        let mut sq = [0.0; 3];
        let mut cross = [0.0; 3];
        let mut energy = 0.0;
        for _ in 0..n {
            let u = m.draw(&point(), &no_slip(), &FlowScales::default(), &mut rng).u;
            for i in 0..3 {
                sum[i] += u[i];
                sq[i] += u[i] * u[i];
                cross[i] += u[i] * u[(i + 1) % 3];
            }
            energy += u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
        }
        let tol = |c: f64| 4.0 * c / nf.sqrt();
        for i in 0..3 {
            assert!((sum[i] / nf).abs() < tol(s2.sqrt()));
            assert!((sq[i] / nf - s2).abs() < tol(s2 * 2f64.sqrt()), "<u_{i}^2> = {}", sq[i] / nf);
            assert!((cross[i] / nf).abs() < tol(s2), "cross {i} = {}", cross[i] / nf);
        }
        assert!((energy / nf - 2.0 * K).abs() < tol(s2 * 6f64.sqrt()), "<u_i u_i> = {}", energy / nf);
    }

    #[test]
    fn mean_duration_without_slip_is_c0_tl() {
        // Exponential lifetimes: standard deviation = mean, so the standard error of the
        // mean of N = 200 000 is C0 T_l / sqrt(N); tolerance 4 standard errors. The fraction
        // of lifetimes above the mean is exp(-1), standard error sqrt(p(1-p)/N).
        let m = EddyInteraction::default();
        let n = 200_000;
        let nf = n as f64;
        let mut rng = stream(36, 0);
        let d: Vec<f64> =
            (0..n).map(|_| m.draw(&point(), &no_slip(), &FlowScales::default(), &mut rng).duration).collect();
        let tau = lifetime_mean();
        let mean = d.iter().sum::<f64>() / nf;
        assert!((mean - tau).abs() < 4.0 * tau / nf.sqrt(), "mean lifetime {mean} vs {tau}");
        let p = (-1.0f64).exp();
        let above = d.iter().filter(|&&t| t > tau).count() as f64 / nf;
        assert!((above - p).abs() < 4.0 * (p * (1.0 - p) / nf).sqrt());
    }

    #[test]
    fn crossing_time_shortens_but_never_lengthens() {
        // Same stream with and without slip: same velocities and lifetimes; with slip the
        // duration is min(t_e, t_c) with t_c from eq 37 when l_e < slip t_p.
        let m = EddyInteraction::default();
        let slip = ParticleSlip { slip: 0.5, response_time: 0.2 };
        let reach = 0.5 * 0.2;
        let s = (2.0 * K / 3.0).sqrt();
        let (mut a, mut b) = (stream(37, 1), stream(37, 1));
        let mut shortened = 0;
        for _ in 0..10_000 {
            let free = m.draw(&point(), &no_slip(), &FlowScales::default(), &mut a);
            let cross = m.draw(&point(), &slip, &FlowScales::default(), &mut b);
            assert_eq!(free.u, cross.u);
            assert!(cross.duration <= free.duration);
            let l_e = free.duration * s;
            if l_e < reach {
                let t_c = -0.2 * (1.0 - l_e / reach).ln();
                assert_relative_eq!(cross.duration, t_c.min(free.duration), max_relative = 1e-12);
                shortened += usize::from(cross.duration < free.duration);
            } else {
                assert_eq!(cross.duration, free.duration);
            }
        }
        assert!(shortened > 5_000, "crossing rarely active: {shortened}");
        // infinite response time: straight crossing at the slip speed
        let t_c = EddyInteraction::crossing_time(0.01, &ParticleSlip { slip: 0.5, response_time: f64::INFINITY });
        assert_eq!(t_c, Some(0.02));
        assert_eq!(EddyInteraction::crossing_time(0.2, &slip), None);
        assert_eq!(EddyInteraction::crossing_time(0.01, &no_slip()), None);
    }

    #[test]
    fn same_stream_same_draws_other_stream_differs() {
        let m = EddyInteraction::default();
        let slip = ParticleSlip { slip: 0.1, response_time: 0.05 };
        let run = |k: u64| {
            let mut rng = stream(11, k);
            (0..16).map(|_| m.draw(&point(), &slip, &FlowScales::default(), &mut rng)).collect::<Vec<_>>()
        };
        assert_eq!(run(5), run(5));
        assert_ne!(run(5), run(6));
    }

    #[test]
    fn simulated_diffusivity_matches_mean_field() {
        // 10 000 tracers (zero slip) over t = 100 C0 T_l; lifetimes are memoryless so a
        // fresh eddy at t = 0 is already stationary. Finite-time expectation
        // <dz^2>/(2t) = D (1 - (tau/t)(1 - exp(-t/tau))); relative standard error of
        // <dz^2> about sqrt(2/N) = 1.4 %. Tolerance: 4 sample standard errors.
        let m = EddyInteraction::default();
        let tau = lifetime_mean();
        let t_end = 100.0 * tau;
        let s = FlowScales::default();
        let dz = displacements(&m, &point(), &s, 10_000, t_end, 99, &|_: &mut Rng| 1.0);
        let sq: Vec<f64> = dz.iter().map(|z| z * z / (2.0 * t_end)).collect();
        let (est, se) = mean_se(&sq);
        let d = m.diffusivity(&point(), &s);
        assert_relative_eq!(d, 2.0 * K / 3.0 * tau, max_relative = 1e-14);
        let expected = d * (1.0 - tau / t_end * (1.0 - (-t_end / tau).exp()));
        assert!(se < 0.02 * expected);
        assert!((est - expected).abs() < 4.0 * se, "D_sim = {est} +- {se}, D = {expected}");
    }

    #[test]
    fn schmidt_number_with_k_over_omega() {
        let m = EddyInteraction::default();
        let d = m.diffusivity(&point(), &FlowScales::default());
        assert_relative_eq!((K / OMEGA) / d, 9.0 * 0.09 / 3.0, max_relative = 1e-14);
    }

    #[test]
    fn degenerate_turbulence_gives_no_nan() {
        let m = EddyInteraction::default();
        let s = FlowScales::default();
        let slip = ParticleSlip { slip: 0.5, response_time: 0.2 };
        let mut rng = stream(3, 3);
        for omega in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let tp = TurbulencePoint { k: K, omega, ..TurbulencePoint::default() };
            let d = m.draw(&tp, &slip, &s, &mut rng);
            assert_eq!(d, FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY });
            assert_eq!(m.diffusivity(&tp, &s), 0.0);
        }
        for k in [0.0, -1e-3, f64::NAN] {
            let tp = TurbulencePoint { k, omega: OMEGA, ..TurbulencePoint::default() };
            let d = m.draw(&tp, &slip, &s, &mut rng);
            assert_eq!(d.u, [0.0; 3]);
            assert!(d.duration.is_finite() && d.duration >= 0.0);
            assert_eq!(m.diffusivity(&tp, &s), 0.0);
        }
    }

    #[test]
    fn validate_names_the_key() {
        assert_eq!(EddyInteraction { c0: 0.0, ..EddyInteraction::default() }.validate().unwrap_err().key, "c0");
        assert_eq!(EddyInteraction { c0: -3.0, ..EddyInteraction::default() }.validate().unwrap_err().key, "c0");
        assert_eq!(EddyInteraction { c0: 21.0, ..EddyInteraction::default() }.validate().unwrap_err().key, "c0");
        assert_eq!(EddyInteraction { c_mu: 0.0, ..EddyInteraction::default() }.validate().unwrap_err().key, "c_mu");
        assert!(EddyInteraction::default().validate().is_ok());
        assert_eq!(EddyInteraction::default().needs(), Needs::of(&[Field::Tke, Field::Omega]));
        assert!(toml::from_str::<EddyInteraction>("C0 = 3").is_err());
    }

    proptest! {
        #[test]
        fn diffusivity_batch_equals_scalar(
            pts in proptest::collection::vec((0.0f64..1.0, 1e-2f64..1e4), 1..64),
        ) {
            let m = EddyInteraction::default();
            let s = FlowScales::default();
            let tp: Vec<TurbulencePoint> =
                pts.iter().map(|&(k, omega)| TurbulencePoint { k, omega, ..TurbulencePoint::default() }).collect();
            let mut out = vec![f64::NAN; tp.len()];
            m.diffusivity_batch(&tp, &s, &mut out);
            for (o, t) in out.iter().zip(&tp) {
                prop_assert_eq!(*o, m.diffusivity(t, &s));
                prop_assert!(o.is_finite() && *o >= 0.0);
            }
        }

        #[test]
        fn duration_positive_and_at_most_lifetime(
            k in 1e-6f64..1.0, omega in 1e-2f64..1e4, slip in 0.0f64..2.0, tp in 1e-4f64..1.0, seed in 0u64..1000,
        ) {
            let m = EddyInteraction::default();
            let t = TurbulencePoint { k, omega, ..TurbulencePoint::default() };
            let p = ParticleSlip { slip, response_time: tp };
            let free = m.draw(&t, &no_slip(), &FlowScales::default(), &mut stream(seed, 0));
            let d = m.draw(&t, &p, &FlowScales::default(), &mut stream(seed, 0));
            prop_assert!(d.duration >= 0.0 && d.duration <= free.duration);
            prop_assert!(d.u.iter().all(|u| u.is_finite()));
        }
    }
}
