//! Discrete random walk of Maurin et al. (2015).

use rand_distr::{Distribution, StandardNormal};
use saltus_core::closure::Family;
use saltus_core::rng::Rng;
use saltus_core::{
    register_model, Describe, Field, FlowScales, Fluctuation, FluctuationDraw, Limit, Needs, ParticleSlip,
    TurbulencePoint,
};
use serde::{Deserialize, Serialize};

use super::MeanField;
use saltus_core::DriftForm;

/// Discrete random walk (DRW) tied to the Reynolds shear stress
///
/// u'_z = lambda_1,  u'_x = -u'_z + lambda_2,  u'_y = 0 (lambda_3 with `spanwise`),  lambda_i ~ N(0, sigma^2),
/// sigma = sqrt(R_xz / (rho_f eps)), held for tau_t = w_d / U_f;
/// so <u'_x u'_z> = -sigma^2, <u'_z^2> = sigma^2, <u'_x^2> = 2 sigma^2.
///
/// * Source: Maurin et al. 2015 eqs 15-16 and the text after them (sigma from the local
///   Reynolds shear stress, redraw every eddy turnover time tau_t = water depth / mean
///   fluid velocity).
/// * Defaults: `period` absent, i.e. tau_t = [`FlowScales::depth`] /
///   |[`FlowScales::bulk_velocity`]|. Give `period` (s) to impose a fixed redraw period.
///   `mean_field = "gradient"` (Chassagne eq 4.4); `ito` gives the flux -d(D phi)/dz, the
///   diffusion limit of draws whose amplitude is set where they are drawn ([`MeanField`]).
/// * `above_bed` absent: the draws apply at every height (Maurin et al. 2015 section II C 3
///   says nothing of the bed). Give `above_bed = phi_b` for the DRW as the peer code
///   applies it (YADE `HydroForceEngine::turbulentFluctuation` with the bed elevation of
///   Maurin's 2017 script of the Frey runs, `turbulentFluctuationPY`, which uses phi_b =
///   0.5): a particle whose centre is at or below the bed elevation when it draws gets no
///   fluctuation until its next draw; the bed elevation is the top of the highest peak of
///   the solid fraction above phi_b ([`saltus_core::Fluctuation::above_bed`]). The
///   mean-field face is unchanged.
/// * `spanwise = false`: u'_y = 0, the paper's two components. `spanwise = true` adds the
///   peer code's third, u'_y = sigma lambda_3 with lambda_3 ~ N(0, 1) drawn after lambda_1
///   and lambda_2 (YADE `HydroForceEngine::turbulentFluctuation`, 2017, which draws three
///   normals per grain). In a channel one grain wide it pushes the grains onto the side
///   walls, where they rub (`particles.wall_friction`). The mean field is unchanged (the
///   diffusivity is wall-normal).
/// * Valid range: `period` > 0 when given; `above_bed` in (0, 1). Needs the Reynolds shear stress
///   ([`TurbulencePoint::reynolds_stress`], already R_xz/(rho_f eps)), e.g. from
///   `mixing_length`; refused on laminar flow.
///
/// Mean-field diffusivity. The wall-normal velocity seen is piecewise constant, redrawn
/// independently every tau_t. For a tracer observed at a uniformly random phase of its
/// period, u'_z(t) and u'_z(t + s) are equal when no redraw falls in between (probability
/// max(0, 1 - s/tau_t)) and independent otherwise, so the autocorrelation is
/// R(s) = sigma^2 max(0, 1 - s/tau_t), the Lagrangian integral time is
/// T_L = int_0^inf R/sigma^2 ds = tau_t/2, and Taylor's theorem gives
/// D = sigma^2 T_L = sigma^2 tau_t / 2 (over a finite time t >= tau_t,
/// <dz^2>/(2t) = D (1 - tau_t/(3t))). This is the tracer value. A particle responding with a
/// linear drag has the same long-time limit (a first-order filter has unit gain at zero
/// frequency) but a smaller displacement variance at finite times, and in a real flow
/// crossing trajectories shorten the correlation time: for inertial particles D is an
/// upper bound.
///
/// Decisions:
/// * Maurin's model is two-component (x, z); u'_y = 0 unless `spanwise`.
/// * Random numbers: two standard normals per draw, lambda_1 first, always consumed; a third
///   after them with `spanwise`, so x and z are the same draws with or without it.
/// * A negative or NaN `reynolds_stress` counts as 0 (no fluctuation).
/// * When no turnover time is defined (bulk velocity 0, zero or non-finite depth) the draw
///   holds forever (`duration = inf`) and D = 0 (a frozen velocity is ballistic, not
///   diffusive): never a NaN. A solver starting from rest should redraw when the flow
///   scales change, or set `period`.
/// * The model returns full periods; a solver that starts every particle with a fresh
///   eddy at the same instant synchronises them, so it should shorten the first duration
///   by a uniform random fraction (random phase), as the diffusivity test does.
/// * Declared limit: D >= 0 (the stress is clamped at 0 and tau is positive or D = 0).
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "drw",
    source = "Maurin et al. 2015 eqs 15-16",
    equation = "u_z = l1, u_x = -u_z + l2, l1,l2 ~ N(0, R_xz/(rho_f eps)), held tau = depth/U; D = sigma^2 tau/2",
    limits = [Limit::NonNegative]
)]
pub struct DiscreteRandomWalk {
    /// fixed redraw period
    #[serde(skip_serializing_if = "Option::is_none")]
    #[param(range = "(0, inf)", unit = "s")]
    pub period: Option<f64>,
    /// mean-field form of the drift: `ito` (the draws' diffusion limit) or `gradient`
    pub mean_field: MeanField,
    /// draw only above the bed: the top of the highest peak of phi above this value
    #[serde(skip_serializing_if = "Option::is_none")]
    #[param(range = "(0, 1)", unit = "-")]
    pub above_bed: Option<f64>,
    /// draw the spanwise component too (the peer code's three components)
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub spanwise: bool,
}

impl DiscreteRandomWalk {
    /// Redraw period: `period` if given, else depth / |bulk velocity|; infinite when
    /// neither defines a positive finite time.
    pub fn turnover_time(&self, s: &FlowScales) -> f64 {
        let tau = match self.period {
            Some(p) => p,
            None => s.depth / s.bulk_velocity.abs(),
        };
        if tau.is_finite() && tau > 0.0 {
            tau
        } else {
            f64::INFINITY
        }
    }

    /// Standard deviation sigma = sqrt(R_xz / (rho_f eps)); 0 for a negative or NaN stress.
    pub fn sigma(t: &TurbulencePoint) -> f64 {
        t.reynolds_stress.max(0.0).sqrt()
    }
}

#[typetag::serde(name = "drw")]
impl Fluctuation for DiscreteRandomWalk {
    fn needs(&self) -> Needs {
        Needs::of(&[Field::ReynoldsStress])
    }

    fn draw(&self, t: &TurbulencePoint, _p: &ParticleSlip, s: &FlowScales, rng: &mut Rng) -> FluctuationDraw {
        let sigma = Self::sigma(t);
        let l1: f64 = StandardNormal.sample(rng);
        let l2: f64 = StandardNormal.sample(rng);
        let uz = sigma * l1;
        let uy = if self.spanwise {
            let l3: f64 = StandardNormal.sample(rng);
            sigma * l3
        } else {
            0.0
        };
        FluctuationDraw { u: [-uz + sigma * l2, uy, uz], duration: self.turnover_time(s) }
    }

    fn drift_form(&self) -> DriftForm {
        self.mean_field.form()
    }

    fn above_bed(&self) -> Option<f64> {
        self.above_bed
    }

    fn diffusivity(&self, t: &TurbulencePoint, s: &FlowScales) -> f64 {
        let tau = self.turnover_time(s);
        if tau.is_finite() {
            t.reynolds_stress.max(0.0) * tau / 2.0
        } else {
            0.0
        }
    }
}

register_model!(Family::Fluctuation, "drw", Fluctuation, DiscreteRandomWalk);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluctuation::sim::{displacements, mean_se};
    use approx::assert_relative_eq;
    use proptest::prelude::*;
    use rand::Rng as _;
    use saltus_core::rng::{stream, Rng};

    const SIGMA: f64 = 0.05;

    fn point() -> TurbulencePoint {
        TurbulencePoint { reynolds_stress: SIGMA * SIGMA, ..TurbulencePoint::default() }
    }
    /// The model a scene's `closures.fluctuation` table gives back.
    fn read_back(text: &str) -> Box<dyn Fluctuation> {
        saltus_core::scene::closure_from_value(
            toml::Value::Table(text.parse().unwrap()),
            Family::Fluctuation,
            std::path::Path::new("drw.toml"),
            "closures.fluctuation",
        )
        .unwrap()
    }

    fn scales() -> FlowScales {
        FlowScales { depth: 0.1, bulk_velocity: 1.0 }
    }

    /// Four standard errors of a sample mean over `n` draws of a quantity whose standard
    /// deviation is `c`: the tolerance of the moment tests.
    fn four_standard_errors(c: f64, n: usize) -> f64 {
        4.0 * c / (n as f64).sqrt()
    }

    /// Sample means and second moments <u_i u_j> of `n` draws from `stream(seed, 0)`.
    fn moments(m: &DiscreteRandomWalk, seed: u64, n: usize) -> ([f64; 3], [[f64; 3]; 3]) {
        let mut rng = stream(seed, 0);
        let (mut mean, mut uu) = ([0.0; 3], [[0.0; 3]; 3]);
        for _ in 0..n {
            let d = m.draw(&point(), &ParticleSlip::default(), &scales(), &mut rng);
            for ((m_i, uu_i), u_i) in mean.iter_mut().zip(uu.iter_mut()).zip(d.u) {
                *m_i += u_i / n as f64;
                for (uu_ij, u_j) in uu_i.iter_mut().zip(d.u) {
                    *uu_ij += u_i * u_j / n as f64;
                }
            }
        }
        (mean, uu)
    }

    #[test]
    fn second_moments_match_maurin() {
        // N = 200 000 draws, fixed seed. Standard errors of the sample moments for Gaussian
        // lambdas: <u_z^2>: sigma^2 sqrt(2/N); <u_x u_z> = <-l1^2 + l1 l2>: sigma^2 sqrt(3/N);
        // <u_x^2> (u_x ~ N(0, 2 sigma^2)): sigma^2 sqrt(8/N); means: sigma sqrt(1/N),
        // sigma sqrt(2/N). Tolerance: 4 standard errors.
        let m = DiscreteRandomWalk::default();
        let n = 200_000;
        let d = m.draw(&point(), &ParticleSlip::default(), &scales(), &mut stream(2015, 1));
        assert_eq!(d.duration, 0.1);
        let (mean, uu) = moments(&m, 2015, n);
        assert_eq!((mean[1], uu[1][1]), (0.0, 0.0));
        let (sx, sz, sxx, szz, sxz) = (mean[0], mean[2], uu[0][0], uu[2][2], uu[0][2]);
        let s2 = SIGMA * SIGMA;
        let tol = |c: f64| four_standard_errors(c, n);
        assert!(sz.abs() < tol(SIGMA));
        assert!(sx.abs() < tol(SIGMA * 2f64.sqrt()));
        assert!((szz - s2).abs() < tol(s2 * 2f64.sqrt()), "<u_z^2> = {szz}");
        assert!((sxz + s2).abs() < tol(s2 * 3f64.sqrt()), "<u_x u_z> = {sxz}");
        assert!((sxx - 2.0 * s2).abs() < tol(s2 * 8f64.sqrt()), "<u_x^2> = {sxx}");
    }

    #[test]
    fn same_stream_same_draws_other_stream_differs() {
        let m = DiscreteRandomWalk::default();
        let run = |k: u64| {
            let mut rng = stream(7, k);
            (0..16).map(|_| m.draw(&point(), &ParticleSlip::default(), &scales(), &mut rng)).collect::<Vec<_>>()
        };
        assert_eq!(run(3), run(3));
        assert_ne!(run(3), run(4));
    }

    #[test]
    fn simulated_diffusivity_matches_mean_field() {
        // 10 000 tracers, t = 100 tau, random phase (first eddy runs a uniform fraction of
        // tau). Exact finite-time expectation <dz^2>/(2t) = D (1 - tau/(3t)); dz is Gaussian
        // so the relative standard error of <dz^2> is sqrt(2/N) = 1.4 %. Tolerance: 4
        // sample standard errors.
        let m = DiscreteRandomWalk::default();
        let tau = 0.1;
        let t_end = 100.0 * tau;
        let dz = displacements(&m, &point(), &scales(), 10_000, t_end, 42, &|r: &mut Rng| r.gen::<f64>());
        let sq: Vec<f64> = dz.iter().map(|z| z * z / (2.0 * t_end)).collect();
        let (est, se) = mean_se(&sq);
        let d = m.diffusivity(&point(), &scales());
        assert_relative_eq!(d, SIGMA * SIGMA * tau / 2.0, max_relative = 1e-14);
        let expected = d * (1.0 - tau / (3.0 * t_end));
        assert!(se < 0.02 * expected);
        assert!((est - expected).abs() < 4.0 * se, "D_sim = {est} +- {se}, D = {expected}");
    }

    #[test]
    fn period_overrides_turnover_and_round_trips() {
        let m = DiscreteRandomWalk { period: Some(0.5), ..DiscreteRandomWalk::default() };
        assert_eq!(m.turnover_time(&scales()), 0.5);
        assert_eq!(m.diffusivity(&point(), &scales()), SIGMA * SIGMA * 0.5 / 2.0);
        let b: Box<dyn Fluctuation> = Box::new(m.clone());
        let text = saltus_core::scene::to_toml_table(&b).unwrap();
        let back = read_back(&text);
        assert_eq!(saltus_core::scene::to_toml_table(&back).unwrap(), text);
        assert_eq!(back.diffusivity(&point(), &scales()), m.diffusivity(&point(), &scales()));
        assert!(text.contains("period = 0.5"));
        let default_text =
            saltus_core::scene::to_toml_table(&(Box::new(DiscreteRandomWalk::default()) as Box<dyn Fluctuation>))
                .unwrap();
        assert!(!default_text.contains("period"));
    }

    #[test]
    fn degenerate_flow_scales_give_no_nan() {
        let m = DiscreteRandomWalk::default();
        let mut rng = stream(1, 1);
        for s in [
            FlowScales { depth: 0.1, bulk_velocity: 0.0 },
            FlowScales { depth: 0.0, bulk_velocity: 1.0 },
            FlowScales { depth: 0.0, bulk_velocity: 0.0 },
            FlowScales { depth: f64::NAN, bulk_velocity: 1.0 },
        ] {
            let d = m.draw(&point(), &ParticleSlip::default(), &s, &mut rng);
            assert_eq!(d.duration, f64::INFINITY);
            assert!(d.u.iter().all(|u| u.is_finite()));
            assert_eq!(m.diffusivity(&point(), &s), 0.0);
        }
        // reverse flow: the turnover time uses |U|
        assert_eq!(m.turnover_time(&FlowScales { depth: 0.1, bulk_velocity: -1.0 }), 0.1);
        // negative or NaN stress: no fluctuation
        for rs in [-1e-3, f64::NAN] {
            let tp = TurbulencePoint { reynolds_stress: rs, ..TurbulencePoint::default() };
            let d = m.draw(&tp, &ParticleSlip::default(), &scales(), &mut rng);
            assert_eq!(d.u, [0.0; 3]);
            assert_eq!(m.diffusivity(&tp, &scales()), 0.0);
        }
    }

    #[test]
    fn validate_names_period_and_needs_reynolds_stress() {
        assert_eq!(
            DiscreteRandomWalk { period: Some(0.0), ..DiscreteRandomWalk::default() }.validate().unwrap_err().key,
            "period"
        );
        assert_eq!(
            DiscreteRandomWalk { period: Some(-1.0), ..DiscreteRandomWalk::default() }.validate().unwrap_err().key,
            "period"
        );
        assert!(DiscreteRandomWalk::default().validate().is_ok());
        assert_eq!(DiscreteRandomWalk::default().needs(), Needs::of(&[Field::ReynoldsStress]));
        assert!(toml::from_str::<DiscreteRandomWalk>("tau = 1.0").is_err());
    }

    #[test]
    fn above_bed_is_validated_kept_and_leaves_draws_and_diffusivity_alone() {
        for bad in [0.0, 1.0, -0.5, f64::NAN] {
            let m = DiscreteRandomWalk { above_bed: Some(bad), ..DiscreteRandomWalk::default() };
            assert_eq!(m.validate().unwrap_err().key, "above_bed");
        }
        let m = DiscreteRandomWalk { above_bed: Some(0.5), ..DiscreteRandomWalk::default() };
        assert!(m.validate().is_ok());
        assert_eq!(m.above_bed(), Some(0.5));
        assert_eq!(DiscreteRandomWalk::default().above_bed(), None);
        // the restriction is the solver's: the closure's draws and mean field are the
        // paper's, stream for stream
        let (mut a, mut b) = (stream(5, 1), stream(5, 1));
        let plain = DiscreteRandomWalk::default();
        for _ in 0..8 {
            assert_eq!(
                m.draw(&point(), &ParticleSlip::default(), &scales(), &mut a),
                plain.draw(&point(), &ParticleSlip::default(), &scales(), &mut b)
            );
        }
        assert_eq!(m.diffusivity(&point(), &scales()), plain.diffusivity(&point(), &scales()));
        let b: Box<dyn Fluctuation> = Box::new(m);
        let text = saltus_core::scene::to_toml_table(&b).unwrap();
        assert!(text.contains("above_bed = 0.5"), "{text}");
        let back = read_back(&text);
        assert_eq!(back.above_bed(), Some(0.5));
        let default_text = saltus_core::scene::to_toml_table(&(Box::new(plain) as Box<dyn Fluctuation>)).unwrap();
        assert!(!default_text.contains("above_bed"));
    }

    #[test]
    fn spanwise_component_is_the_peer_codes_third_normal() {
        // N = 200 000 draws: <u_y> = 0 +- sigma sqrt(1/N), <u_y^2> = sigma^2 +- sigma^2
        // sqrt(2/N), <u_x u_y> = 0 +- sigma^2 sqrt(2/N), <u_y u_z> = 0 +- sigma^2 sqrt(1/N);
        // tolerance 4 standard errors. The x and z parts are the default's draws.
        let m = DiscreteRandomWalk { spanwise: true, ..DiscreteRandomWalk::default() };
        let plain = DiscreteRandomWalk::default();
        let (mut a, mut b) = (stream(9, 2), stream(9, 2));
        let (one, two) = (
            m.draw(&point(), &ParticleSlip::default(), &scales(), &mut a),
            plain.draw(&point(), &ParticleSlip::default(), &scales(), &mut b),
        );
        assert_eq!((one.u[0], one.u[2]), (two.u[0], two.u[2]));
        assert_ne!(one.u[1], 0.0);
        let n = 200_000;
        let (mean, uu) = moments(&m, 2017, n);
        let (sy, syy, sxy, syz) = (mean[1], uu[1][1], uu[0][1], uu[1][2]);
        let s2 = SIGMA * SIGMA;
        let tol = |c: f64| four_standard_errors(c, n);
        assert!(sy.abs() < tol(SIGMA));
        assert!((syy - s2).abs() < tol(s2 * 2f64.sqrt()), "<u_y^2> = {syy}");
        assert!(sxy.abs() < tol(s2 * 2f64.sqrt()), "<u_x u_y> = {sxy}");
        assert!(syz.abs() < tol(s2), "<u_y u_z> = {syz}");
        assert_eq!(m.diffusivity(&point(), &scales()), plain.diffusivity(&point(), &scales()));
        let text = saltus_core::scene::to_toml_table(&(Box::new(m) as Box<dyn Fluctuation>)).unwrap();
        assert!(text.contains("spanwise = true"), "{text}");
        let back = read_back(&text);
        let (mut c, mut d) = (stream(3, 3), stream(3, 3));
        assert_eq!(
            back.draw(&point(), &ParticleSlip::default(), &scales(), &mut c),
            DiscreteRandomWalk { spanwise: true, ..DiscreteRandomWalk::default() }.draw(
                &point(),
                &ParticleSlip::default(),
                &scales(),
                &mut d
            )
        );
        let default_text = saltus_core::scene::to_toml_table(&(Box::new(plain) as Box<dyn Fluctuation>)).unwrap();
        assert!(!default_text.contains("spanwise"));
        assert!(toml::from_str::<DiscreteRandomWalk>("spanwise = 1").is_err());
    }

    proptest! {
        #[test]
        fn diffusivity_batch_equals_scalar(
            rs in proptest::collection::vec(0.0f64..1.0, 1..64),
            depth in 1e-3f64..10.0,
            u in -5.0f64..5.0,
        ) {
            let m = DiscreteRandomWalk::default();
            let s = FlowScales { depth, bulk_velocity: u };
            let tp: Vec<TurbulencePoint> =
                rs.iter().map(|&r| TurbulencePoint { reynolds_stress: r, ..TurbulencePoint::default() }).collect();
            let mut out = vec![f64::NAN; tp.len()];
            m.diffusivity_batch(&tp, &s, &mut out);
            for (o, t) in out.iter().zip(&tp) {
                prop_assert_eq!(*o, m.diffusivity(t, &s));
                prop_assert!(o.is_finite() && *o >= 0.0);
            }
        }
    }
}
