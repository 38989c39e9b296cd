//! A fluctuation model registered at run time: the particle face (one draw: the
//! fluctuation (u_x, u_y, u_z) and how long it holds) and the mean-field face (the
//! wall-normal particle diffusivity over a column, for the Eulerian drift velocity
//! u_d = D grad(phi) / phi of Chassagne et al. 2023 eq 4.4, gradient form).
//!
//! The randomness of a draw is the solver's: the variates the registration declares
//! (standard normal, exponential of rate 1, uniform on [0, 1)) are taken in order from the
//! particle's own seeded stream ([`saltus_core::rng::stream`]) and handed to the function
//! as inputs, so a run is bit-reproducible for a seed on any thread count, and a function
//! that declares the variates a built-in model takes, in its order, sees the same numbers
//! (the eddy interaction model: three normals, then one exponential).

use rand::Rng as _;
use rand_distr::{Distribution, Exp1, StandardNormal};
use saltus_core::rng::Rng;
use saltus_core::runtime::{Shape, Variate, MAX_VARIATES};
use saltus_core::{FlowScales, Fluctuation, FluctuationDraw, Needs, ParticleSlip, TurbulencePoint};

use super::{as_runtime_closure, RuntimeClosure};

/// A fluctuation model whose draw and diffusivity are registered functions.
pub struct RuntimeFluctuation {
    c: RuntimeClosure,
}

as_runtime_closure!(RuntimeFluctuation);

impl RuntimeFluctuation {
    pub(super) fn new(c: RuntimeClosure) -> Self {
        RuntimeFluctuation { c }
    }
}

// typetag's two hidden methods by hand, as for the one-function families (runtime.rs)
impl Fluctuation for RuntimeFluctuation {
    fn typetag_name(&self) -> &'static str {
        self.c.model.name
    }
    fn typetag_deserialize(&self) {}

    fn needs(&self) -> Needs {
        match &self.c.model.shape {
            Shape::Fluctuation { needs, .. } => *needs,
            _ => Needs::NONE,
        }
    }

    fn draw(&self, t: &TurbulencePoint, p: &ParticleSlip, s: &FlowScales, rng: &mut Rng) -> FluctuationDraw {
        let variates: &[Variate] = match &self.c.model.shape {
            Shape::Fluctuation { variates, .. } => variates,
            _ => &[],
        };
        let mut xi = [0.0; MAX_VARIATES];
        for (x, v) in xi.iter_mut().zip(variates) {
            *x = match v {
                Variate::Normal => StandardNormal.sample(rng),
                Variate::Exponential => Exp1.sample(rng),
                Variate::Uniform => rng.gen::<f64>(),
            };
        }
        let point = [t.k, t.omega, t.nu_t, t.reynolds_stress, p.slip, p.response_time];
        let mut inputs: Vec<&[f64]> = point.iter().map(std::slice::from_ref).collect();
        inputs.extend(xi[..variates.len().min(MAX_VARIATES)].iter().map(std::slice::from_ref));
        let mut u = [[0.0]; 4];
        let [ux, uy, uz, duration] = &mut u;
        self.c.call_face(&*self.c.model.function, &[s.depth, s.bulk_velocity], &inputs, &mut [ux, uy, uz, duration]);
        FluctuationDraw { u: [u[0][0], u[1][0], u[2][0]], duration: u[3][0] }
    }

    fn diffusivity(&self, t: &TurbulencePoint, s: &FlowScales) -> f64 {
        let mut out = [0.0];
        self.diffusivity_batch(std::slice::from_ref(t), s, &mut out);
        out[0]
    }

    fn diffusivity_batch(&self, t: &[TurbulencePoint], s: &FlowScales, out: &mut [f64]) {
        let Shape::Fluctuation { diffusivity, .. } = &self.c.model.shape else { return };
        let column = |f: fn(&TurbulencePoint) -> f64| t.iter().map(f).collect::<Vec<f64>>();
        let (k, omega, nu_t, rs) =
            (column(|p| p.k), column(|p| p.omega), column(|p| p.nu_t), column(|p| p.reynolds_stress));
        self.c.call_face(&**diffusivity, &[s.depth, s.bulk_velocity], &[&k, &omega, &nu_t, &rs], &mut [out]);
    }
}
