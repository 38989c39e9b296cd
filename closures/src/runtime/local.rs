//! A granular local rheology registered at run time: friction mu(x) and packing phi(x) of
//! a control number x (I, J or K), one call of the registered function per batch.
//!
//! The control number and the pressure at which the state reaches a given one are the
//! definitions of [`LocalState`] (closed forms, as the built-in `mu_i` and `mu_k` have
//! them); the law is the user's. The packing inverse is the registered inverse when one
//! is given, else the bisection of [`LocalRheology::control_of_packing`] done on the
//! whole array at once: 100 halvings of [-30, 30] in log x, one call of the function per
//! halving on the points not yet resolved, the same arithmetic as the trait's scalar
//! bisection, so that a law without inverse is inverted as a compiled law without a
//! closed form is.

use saltus_core::runtime::{Control, Shape};
use saltus_core::{GranularStress, LocalRheology, LocalState};

use super::{as_runtime_closure, RuntimeClosure};

/// Grain keywords of a granular closure built outside a scene (`closure eval`, `closure
/// check`): the glass beads of Chassagne et al. 2023, whose restitution and friction are
/// the defaults of `[particles]` (d = 6 mm, rho_p = 2500 kg/m^3, e = 0.7, mu_p = 0.4).
pub(super) const UNSET_GRAIN: [f64; 4] = [6e-3, 2500.0, 0.7, 0.4];

/// Halvings of the packing inverse without a registered inverse (the trait's bisection).
const HALVINGS: usize = 100;

/// A local rheology whose friction and packing are a registered function.
pub struct RuntimeLocal {
    c: RuntimeClosure,
    control: Control,
    /// alpha of K = J + alpha I^2 (NaN for the other control numbers)
    alpha: f64,
    /// diameter, density, restitution and friction of `[particles]`, the function's keywords
    grain: [f64; 4],
}

as_runtime_closure!(RuntimeLocal);

impl RuntimeLocal {
    pub(super) fn new(c: RuntimeClosure) -> Self {
        let control = match c.model.shape {
            Shape::Local { control, .. } => control,
            _ => Control::Inertial,
        };
        let alpha = c.param("alpha");
        RuntimeLocal { c, control, alpha, grain: UNSET_GRAIN }
    }

    /// Friction and packing of `x` into `mu` and `phi`.
    fn rheology(&self, x: &[f64], mu: &mut [f64], phi: &mut [f64]) {
        self.c.call_face(&*self.c.model.function, &self.grain, &[x], &mut [mu, phi]);
    }
}

impl LocalRheology for RuntimeLocal {
    fn control_name(&self) -> &'static str {
        self.control.name()
    }

    fn control_number(&self, s: &LocalState) -> f64 {
        match self.control {
            Control::Inertial => s.inertial_number(),
            Control::Viscous => s.viscous_number(),
            Control::Combined => {
                let (i, j) = (s.inertial_number(), s.viscous_number());
                // sheared at zero pressure; alpha = 0 must not turn 0 * inf into NaN
                if j.is_infinite() {
                    f64::INFINITY
                } else {
                    j + self.alpha * i * i
                }
            }
        }
    }

    fn friction(&self, x: f64) -> f64 {
        let (mut mu, mut phi) = ([0.0], [0.0]);
        self.rheology(&[x], &mut mu, &mut phi);
        mu[0]
    }

    fn packing(&self, x: f64) -> f64 {
        let (mut mu, mut phi) = ([0.0], [0.0]);
        self.rheology(&[x], &mut mu, &mut phi);
        phi[0]
    }

    fn control_of_packing(&self, phi: f64) -> f64 {
        let mut out = [0.0];
        self.control_of_packing_batch(&[phi], &mut out);
        out[0]
    }

    fn pressure_at(&self, s: &LocalState, x: f64) -> f64 {
        let g = s.shear_rate.abs();
        if g == 0.0 || x.is_infinite() {
            return 0.0;
        }
        if x <= 0.0 || x.is_nan() {
            return f64::INFINITY;
        }
        match self.control {
            // I = d |gamma_dot| sqrt(rho_p / p)  =>  p = rho_p (d gamma_dot / I)^2
            Control::Inertial => {
                let r = s.diameter * s.shear_rate / x;
                s.particle_density * r * r
            }
            // J = eta_f |gamma_dot| / p
            Control::Viscous => s.fluid_viscosity * g / x,
            // K = (eta_f |gamma_dot| + alpha rho_p d^2 gamma_dot^2) / p
            Control::Combined => {
                (s.fluid_viscosity * g + self.alpha * s.particle_density * s.diameter * s.diameter * g * g) / x
            }
        }
    }

    fn eval_batch(&self, x: &[f64], mu: &mut [f64], phi: &mut [f64]) {
        self.rheology(x, mu, phi);
    }

    fn control_of_packing_batch(&self, phi: &[f64], out: &mut [f64]) {
        if let Shape::Local { inverse: Some(inverse), .. } = &self.c.model.shape {
            self.c.call_face(&**inverse, &self.grain, &[phi], &mut [out]);
            return;
        }
        // the trait's bisection, on every unresolved point at once
        let jammed = self.packing(0.0);
        let mut open = Vec::new();
        for (i, (o, &p)) in out.iter_mut().zip(phi).enumerate() {
            if p >= jammed {
                *o = 0.0;
            } else if p <= 0.0 || p.is_nan() {
                *o = f64::INFINITY;
            } else {
                open.push(i);
            }
        }
        if open.is_empty() {
            return;
        }
        let n = open.len();
        let (mut lo, mut hi) = (vec![-30.0f64; n], vec![30.0f64; n]);
        let (mut x, mut mu, mut at) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for _ in 0..HALVINGS {
            for ((xi, l), h) in x.iter_mut().zip(&lo).zip(&hi) {
                *xi = (0.5 * (l + h)).exp();
            }
            self.rheology(&x, &mut mu, &mut at);
            for (k, &i) in open.iter().enumerate() {
                let mid = 0.5 * (lo[k] + hi[k]);
                if at[k] > phi[i] {
                    lo[k] = mid;
                } else {
                    hi[k] = mid;
                }
            }
        }
        for (k, &i) in open.iter().enumerate() {
            out[i] = (0.5 * (lo[k] + hi[k])).exp();
        }
    }
}

// typetag's two hidden methods by hand, as for the one-function families (runtime.rs)
impl GranularStress for RuntimeLocal {
    fn typetag_name(&self) -> &'static str {
        self.c.model.name
    }
    fn typetag_deserialize(&self) {}

    fn as_local(&self) -> Option<&dyn LocalRheology> {
        Some(self)
    }

    fn inherit(&mut self, _given: &toml::Table, particles: &saltus_core::Grains) {
        self.grain = [particles.diameter, particles.density, particles.restitution, particles.friction];
    }
}
