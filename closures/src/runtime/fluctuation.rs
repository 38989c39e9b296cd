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
//! (the eddy interaction model: three normals, then one exponential). A chunk of draws
//! ([`Fluctuation::draw_batch`]) is one call of the function on arrays, each draw's
//! variates from its own particle's stream.

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
        let mut out = [FluctuationDraw::default()];
        self.draw_batch(std::slice::from_ref(t), std::slice::from_ref(p), s, &mut [rng], &mut out);
        out[0]
    }

    /// One call of the registered draw for the chunk: the variates of draw `j` are taken
    /// from `rng[j]` in the declared order (all of one draw before the next stream), then
    /// the function sees the chunk's inputs and variates as arrays.
    fn draw_batch(
        &self,
        t: &[TurbulencePoint],
        p: &[ParticleSlip],
        s: &FlowScales,
        rng: &mut [&mut Rng],
        out: &mut [FluctuationDraw],
    ) {
        let variates: &[Variate] = match &self.c.model.shape {
            Shape::Fluctuation { variates, .. } => &variates[..variates.len().min(MAX_VARIATES)],
            _ => &[],
        };
        let n = out.len().min(t.len()).min(p.len()).min(rng.len());
        let mut xi = vec![vec![0.0; n]; variates.len()];
        for (j, r) in rng.iter_mut().take(n).enumerate() {
            for (x, v) in xi.iter_mut().zip(variates) {
                x[j] = match v {
                    Variate::Normal => StandardNormal.sample(&mut **r),
                    Variate::Exponential => Exp1.sample(&mut **r),
                    Variate::Uniform => r.gen::<f64>(),
                };
            }
        }
        let column = |f: &dyn Fn(usize) -> f64| (0..n).map(f).collect::<Vec<f64>>();
        let point = [
            column(&|j| t[j].k),
            column(&|j| t[j].omega),
            column(&|j| t[j].nu_t),
            column(&|j| t[j].reynolds_stress),
            column(&|j| p[j].slip),
            column(&|j| p[j].response_time),
        ];
        let inputs: Vec<&[f64]> = point.iter().chain(&xi).map(|c| &c[..]).collect();
        let mut u = vec![vec![0.0; n]; 4];
        let [ux, uy, uz, duration] = &mut u[..] else { return };
        self.c.call_face(&*self.c.model.function, &[s.depth, s.bulk_velocity], &inputs, &mut [ux, uy, uz, duration]);
        for (j, o) in out.iter_mut().take(n).enumerate() {
            *o = FluctuationDraw { u: [u[0][j], u[1][j], u[2][j]], duration: u[3][j] };
        }
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
