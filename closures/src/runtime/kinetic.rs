//! A kinetic-theory coefficient set registered at run time: g0, F1-F4 and e_eff of
//! Chassagne et al. 2023 eqs 2.19-2.22 (table 1) as a function of phi and, with
//! saltation, of the saltation input of eq 3.6 (sqrt(T) and the drag coefficient K of
//! eq 2.10), one call per column.
//!
//! The rest of the frictional-collisional stress is the built-in one
//! ([`FrictionalCollisional`]) at the model's parameters `p0`, `phi_rlp`, `phi_max` and
//! `static_friction`: the Johnson-Jackson elastic pressure (eq 2.14) and its Coulomb
//! friction (eq 2.15), the stresses of the coefficients (eqs 2.19-2.22), the drag
//! dissipation factor (eq 2.25 or 3.13) and the readings of a measured state backwards
//! (eq 3.1-3.2).

use saltus_core::runtime::Shape;
use saltus_core::{GranularStress, JohnsonJacksonElastic, KineticCoefficients, KineticTheory, SaltationInput};

use super::local::UNSET_GRAIN;
use super::{as_runtime_closure, RuntimeClosure};
use crate::granular::kinetic::{DragDissipation, Saltation};
use crate::granular::{FrictionalCollisional, StaticFriction};

/// A frictional-collisional stress whose kinetic coefficients are a registered function.
pub struct RuntimeKinetic {
    c: RuntimeClosure,
    /// the elastic law, drag dissipation and stresses of the coefficients
    built_in: FrictionalCollisional,
    /// diameter, density, restitution and friction of `[particles]`, the function's keywords
    grain: [f64; 4],
}

as_runtime_closure!(RuntimeKinetic);

impl RuntimeKinetic {
    /// The adapter; the parameters must give 0 < phi_rlp < phi_max < 1.
    pub(super) fn new(c: RuntimeClosure) -> Result<Self, String> {
        let (saltation, linear) = match c.model.shape {
            Shape::Kinetic { saltation, linear_drag_dissipation } => (saltation, linear_drag_dissipation),
            _ => (false, false),
        };
        let built_in = FrictionalCollisional {
            p0: c.param("p0"),
            phi_rlp: c.param("phi_rlp"),
            phi_max: c.param("phi_max"),
            static_friction: StaticFriction::Value(c.param("static_friction")),
            drag_dissipation: if linear { DragDissipation::Linear } else { DragDissipation::Quadratic },
            saltation: Saltation { enabled: saltation, ..Saltation::default() },
            ..FrictionalCollisional::default()
        };
        if !(built_in.phi_rlp > 0.0 && built_in.phi_rlp < built_in.phi_max && built_in.phi_max < 1.0) {
            return Err(format!(
                "closure `{}`: phi_rlp = {} and phi_max = {} must satisfy 0 < phi_rlp < phi_max < 1",
                c.model.name, built_in.phi_rlp, built_in.phi_max
            ));
        }
        Ok(RuntimeKinetic { c, built_in, grain: UNSET_GRAIN })
    }
}

impl KineticTheory for RuntimeKinetic {
    fn phi_max(&self) -> f64 {
        self.built_in.phi_max
    }
    fn elastic_law(&self) -> JohnsonJacksonElastic {
        self.built_in.elastic()
    }
    fn elastic_pressure(&self, phi: f64) -> f64 {
        self.built_in.elastic_pressure(phi)
    }
    fn elastic_pressure_derivative(&self, phi: f64) -> f64 {
        self.built_in.elastic_pressure_derivative(phi)
    }
    fn static_friction(&self) -> f64 {
        self.built_in.static_friction()
    }
    fn coefficients(&self, phi: f64, salt: Option<&SaltationInput>) -> KineticCoefficients {
        let mut out = [KineticCoefficients::default()];
        self.coefficients_batch(&[phi], salt.map(std::slice::from_ref), &mut out);
        out[0]
    }
    fn drag_dissipation_factor(&self, cd_inf: f64, cd: f64) -> f64 {
        self.built_in.drag_dissipation_factor(cd_inf, cd)
    }
    fn saltation_enabled(&self) -> bool {
        self.built_in.saltation_enabled()
    }
    fn kinetic_pressure(&self, c: &KineticCoefficients, rho_p: f64, t: f64) -> f64 {
        self.built_in.kinetic_pressure(c, rho_p, t)
    }
    fn shear_viscosity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        self.built_in.shear_viscosity(c, rho_p, d, sqrt_t)
    }
    fn viscosity_coefficient(&self, tau: f64, gamma_dot: f64, rho_p: f64, d: f64, t: f64) -> f64 {
        self.built_in.viscosity_coefficient(tau, gamma_dot, rho_p, d, t)
    }
    fn conductivity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        self.built_in.conductivity(c, rho_p, d, sqrt_t)
    }
    fn dissipation(&self, c: &KineticCoefficients, rho_p: f64, d: f64, t: f64) -> f64 {
        self.built_in.dissipation(c, rho_p, d, t)
    }
    fn dissipation_per_temperature(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        self.built_in.dissipation_per_temperature(c, rho_p, d, sqrt_t)
    }
    fn radial_distribution_of_pressure(&self, c: &KineticCoefficients, phi: f64, p: f64, rho_p: f64, t: f64) -> f64 {
        self.built_in.radial_distribution_of_pressure(c, phi, p, rho_p, t)
    }
    fn radial_distribution_regressor(&self, phi: f64) -> f64 {
        self.built_in.radial_distribution_regressor(phi)
    }
    fn saltation_input(&self, phi: f64, t: f64, beta: f64, rho_p: f64, d: f64) -> SaltationInput {
        self.built_in.saltation_input(phi, t, beta, rho_p, d)
    }

    fn coefficients_batch(&self, phi: &[f64], salt: Option<&[SaltationInput]>, out: &mut [KineticCoefficients]) {
        let n = phi.len();
        // the saltation input where the solver gives it (saltation on), else 0
        let (mut sqrt_t, mut k_drag) = (vec![0.0; n], vec![0.0; n]);
        if let Some(salt) = salt.filter(|_| self.saltation_enabled()) {
            for ((t, k), s) in sqrt_t.iter_mut().zip(k_drag.iter_mut()).zip(salt) {
                *t = s.sqrt_t;
                *k = s.k_drag;
            }
        }
        let mut cols = vec![vec![0.0; n]; 6];
        let [g0, f1, f2, f3, f4, e_eff] = &mut cols[..] else { return };
        self.c.call_face(
            &*self.c.model.function,
            &self.grain,
            &[phi, &sqrt_t, &k_drag],
            &mut [g0, f1, f2, f3, f4, e_eff],
        );
        for (i, o) in out.iter_mut().enumerate() {
            *o = KineticCoefficients { g0: g0[i], f1: f1[i], f2: f2[i], f3: f3[i], f4: f4[i], e_eff: e_eff[i] };
        }
    }
}

// typetag's two hidden methods by hand, as for the one-function families (runtime.rs)
impl GranularStress for RuntimeKinetic {
    fn typetag_name(&self) -> &'static str {
        self.c.model.name
    }
    fn typetag_deserialize(&self) {}

    fn as_kinetic(&self) -> Option<&dyn KineticTheory> {
        Some(self)
    }

    fn inherit(&mut self, _given: &toml::Table, particles: &saltus_core::Grains) {
        self.grain = [particles.diameter, particles.density, particles.restitution, particles.friction];
        self.built_in.restitution = particles.restitution;
        self.built_in.friction = particles.friction;
    }
}
