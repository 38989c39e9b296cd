//! Frictional-collisional granular stress: Johnson-Jackson elastic stress + kinetic theory.

use std::fmt;

use saltus_core::closure::Family;
use saltus_core::{
    register_model, Describe, GranularStress, KineticCoefficients, KineticTheory, Limit, SaltationInput,
};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::kinetic::{
    garzo_dufty as gd, saltation, ChialvoSundaresanG0, DragDissipation, RadialDistribution, RestitutionModel, Saltation,
};

/// Static friction mu_s of the Coulomb elastic shear stress tau_el = mu_s p_el.
///
/// TOML: a number (`static_friction = 0.35`) or the string `"from_mu_p"`, the fit of
/// Chassagne et al. 2023 App. B eq B1, mu_s = 0.146 + 0.228 tanh(mu_p / 0.232), of the
/// model's `friction` (0.36 at mu_p = 0.4).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum StaticFriction {
    /// eq B1 of the interparticle friction
    #[default]
    FromMuP,
    /// given value
    Value(f64),
}

impl StaticFriction {
    /// Keyword of [`StaticFriction::FromMuP`].
    pub const KEYWORD: &'static str = "from_mu_p";

    /// App. B eq B1: mu_s = 0.146 + 0.228 tanh(mu_p / 0.232).
    #[inline]
    pub fn fit(mu_p: f64) -> f64 {
        0.146 + 0.228 * (mu_p / 0.232).tanh()
    }

    /// mu_s at interparticle friction `mu_p`.
    #[inline]
    pub fn value(self, mu_p: f64) -> f64 {
        match self {
            Self::FromMuP => Self::fit(mu_p),
            Self::Value(v) => v,
        }
    }
}

impl Serialize for StaticFriction {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::FromMuP => s.serialize_str(Self::KEYWORD),
            Self::Value(v) => s.serialize_f64(*v),
        }
    }
}

impl<'de> Deserialize<'de> for StaticFriction {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = StaticFriction;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a number or \"{}\"", StaticFriction::KEYWORD)
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<StaticFriction, E> {
                Ok(StaticFriction::Value(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<StaticFriction, E> {
                Ok(StaticFriction::Value(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<StaticFriction, E> {
                Ok(StaticFriction::Value(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<StaticFriction, E> {
                if v == StaticFriction::KEYWORD {
                    Ok(StaticFriction::FromMuP)
                } else {
                    Err(E::invalid_value(serde::de::Unexpected::Str(v), &self))
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// Frictional-collisional granular stress (Johnson & Jackson 1987 + kinetic theory)
///
/// ```text
/// p_p = p_el + rho_p F1 T,   tau_p = mu_s p_el + rho_p d F2 sqrt(T) |gamma_dot|
/// p_el = P0 (phi - phi_rlp)^3 / (phi_max - phi)^5  for phi >= phi_rlp, else 0
/// q = -rho_p d F3 sqrt(T) dT/dz,  Gamma = rho_p/d F4' T^1.5,  J_int = -phi(1-phi) K c_J T
/// ```
///
/// * Source: Chassagne, Bonamy & Chauchat 2023 (J. Fluid Mech. 964, A27) eqs 2.12-2.25,
///   table 1, 3.2-3.13, App. B (mu_s), C (e_eff), D (c_J).
/// * Defaults = the paper's PROPOSED model (table 1 right column): `restitution` and
///   `friction` those of `[particles]` (0.7 and 0.4 by default), `p0 = 0.05` Pa, `phi_rlp = 0.57`, `phi_max = 0.635`,
///   `static_friction = "from_mu_p"` (0.36), `g0 = { type = "chialvo_sundaresan_friction" }`,
///   `restitution_model = { type = "jenkins_zhang", e_t = 0 }`,
///   `saltation = { enabled = true, c0 = 5, sigma = 0.5 }`, `drag_dissipation = "quadratic"`.
///   The INITIAL model (table 1 left column) is [`FrictionalCollisional::garzo_dufty_initial`].
/// * Valid range: `restitution` in (0, 1], `friction` in [0, 2], `p0 > 0`,
///   `0 < phi_rlp < phi_max < 1`, numeric `static_friction` in [0, 2].
/// * Decisions: phi < 0 is evaluated as 0. For phi >= phi_max, g0, p_el, its derivative and
///   F1..F3 (and F4 unless e_eff = 1) are +inf, never NaN. F4 uses e_eff, F1..F3 the bare e.
///   The kinetic-part formulas are those of [`super::kinetic::garzo_dufty`].
/// * Declared limits: g0 -> 1 as phi -> 0 (every `g0` form is Carnahan-Starling,
///   1 + 5 phi / 2 + O(phi^2), the Chialvo-Sundaresan ones plus a term of order phi^2). Not declared: the static friction and the packing of a local
///   rheology, since this model is no mu(I) law (its mu_s is the Coulomb ratio of the
///   elastic stress, p_el = 0 below phi_rlp, and phi is an unknown of the temperature
///   balance, not a function of a control number).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "frictional_collisional",
    source = "Chassagne, Bonamy & Chauchat 2023 eqs 2.12-2.25, table 1, 3.2-3.13, App. B-D; Garzo & Dufty 1999; Johnson & Jackson 1987",
    equation = "p = P0 (phi-phi_rlp)^3/(phi_max-phi)^5 + rho_p F1 T, tau = mu_s p_el + rho_p d F2 sqrt(T) |gamma_dot|, Gamma = rho_p/d F4' T^1.5",
    limits = [Limit::Dilute]
)]
pub struct FrictionalCollisional {
    /// normal restitution coefficient e
    #[param(range = "(0, 1]", unit = "-")]
    pub restitution: f64,
    /// interparticle friction coefficient mu_p
    #[param(range = "[0, 2]", unit = "-")]
    pub friction: f64,
    /// elastic modulus P0 of the Johnson-Jackson pressure
    #[param(range = "(0, inf)", unit = "Pa")]
    pub p0: f64,
    /// random loose packing where p_el starts
    #[param(range = "(0, 1)", unit = "-", less_than = phi_max)]
    pub phi_rlp: f64,
    /// maximum packing where g0 and p_el diverge
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_max: f64,
    /// Coulomb static friction mu_s (number, or "from_mu_p": eq B1 of friction)
    #[param(range = "[0, 2]", unit = "-", value = self.static_friction.value(self.friction))]
    pub static_friction: StaticFriction,
    /// dissipation by drag: "linear" (c_J = 3) or "quadratic" (3 + 2 C_D^inf/C_D)
    pub drag_dissipation: DragDissipation,
    /// radial distribution function
    pub g0: RadialDistribution,
    /// effective restitution in F4
    pub restitution_model: RestitutionModel,
    /// saltation correction of F2, F3
    pub saltation: Saltation,
}

impl Default for FrictionalCollisional {
    fn default() -> Self {
        Self {
            restitution: 0.7,
            friction: 0.4,
            p0: 0.05,
            phi_rlp: 0.57,
            phi_max: 0.635,
            static_friction: StaticFriction::FromMuP,
            drag_dissipation: DragDissipation::Quadratic,
            g0: RadialDistribution::default(),
            restitution_model: RestitutionModel::default(),
            saltation: Saltation::default(),
        }
    }
}

impl FrictionalCollisional {
    /// The paper's INITIAL model (table 1 left column, Garzo & Dufty 1999): g0 of
    /// Chialvo-Sundaresan with a = 0.58, plain restitution, no saltation, linear drag
    /// dissipation; elastic part and other parameters as the default.
    pub fn garzo_dufty_initial() -> Self {
        Self {
            g0: RadialDistribution::ChialvoSundaresan(ChialvoSundaresanG0::default()),
            restitution_model: RestitutionModel::Plain {},
            saltation: Saltation::disabled(),
            drag_dissipation: DragDissipation::Linear,
            ..Self::default()
        }
    }

    /// The Johnson-Jackson elastic pressure of this closure (eq 2.14).
    #[inline]
    pub fn elastic(&self) -> saltus_core::JohnsonJacksonElastic {
        saltus_core::JohnsonJacksonElastic { p0: self.p0, phi_rlp: self.phi_rlp, phi_max: self.phi_max }
    }

    /// Radial distribution at `phi` (phi < 0 evaluated as 0).
    #[inline]
    pub fn g0_at(&self, phi: f64) -> f64 {
        self.g0.g0(non_negative(phi), self.phi_max, self.friction)
    }

    /// Effective restitution e_eff used in F4.
    #[inline]
    pub fn effective_restitution(&self) -> f64 {
        self.restitution_model.effective(self.restitution, self.friction)
    }
}

/// The parts of the coefficients that depend on the parameters only, not on phi: the
/// a(mu_p) of g0 (a tanh) and the effective restitution (an atan). A batch computes them
/// once for its column instead of once per point.
#[derive(Clone, Copy)]
struct Invariants {
    a: f64,
    e_eff: f64,
}

impl FrictionalCollisional {
    fn invariants(&self) -> Invariants {
        Invariants { a: self.g0.coefficient_a(self.friction), e_eff: self.effective_restitution() }
    }

    /// [`KineticTheory::coefficients`] with the invariants given.
    #[inline]
    fn coefficients_with(&self, k: Invariants, phi: f64, salt: Option<&SaltationInput>) -> KineticCoefficients {
        let phi = non_negative(phi);
        let e = self.restitution;
        let g0 = self.g0.g0_with_a(phi, self.phi_max, k.a);
        let (eta_k, kappa_k) = (gd::eta_k(phi, e, g0), gd::kappa_k(phi, e, g0));
        let (eta_k, kappa_k) = match salt {
            Some(s) if self.saltation.enabled => {
                let eta_salt = self.saltation.eta_salt(phi, s);
                let kappa_salt = eta_salt / self.saltation.sigma;
                (saltation::harmonic(eta_k, eta_salt), saltation::harmonic(kappa_k, kappa_salt))
            }
            _ => (eta_k, kappa_k),
        };
        KineticCoefficients {
            g0,
            f1: gd::f1(phi, e, g0),
            f2: eta_k + gd::eta_cb(phi, e, g0),
            f3: kappa_k + gd::kappa_cb(phi, e, g0),
            f4: gd::f4(phi, k.e_eff, g0),
            e_eff: k.e_eff,
        }
    }
}

/// phi < 0 -> 0, NaN kept.
#[inline]
fn non_negative(phi: f64) -> f64 {
    if phi < 0.0 {
        0.0
    } else {
        phi
    }
}

impl KineticTheory for FrictionalCollisional {
    fn phi_max(&self) -> f64 {
        self.phi_max
    }

    fn elastic_law(&self) -> saltus_core::JohnsonJacksonElastic {
        self.elastic()
    }

    #[inline]
    fn elastic_pressure(&self, phi: f64) -> f64 {
        self.elastic().pressure(phi)
    }

    #[inline]
    fn elastic_pressure_derivative(&self, phi: f64) -> f64 {
        self.elastic().derivative(phi)
    }

    fn static_friction(&self) -> f64 {
        self.static_friction.value(self.friction)
    }

    fn coefficients(&self, phi: f64, salt: Option<&SaltationInput>) -> KineticCoefficients {
        self.coefficients_with(self.invariants(), phi, salt)
    }

    fn coefficients_batch(&self, phi: &[f64], salt: Option<&[SaltationInput]>, out: &mut [KineticCoefficients]) {
        let k = self.invariants();
        match salt {
            Some(salt) => {
                for ((o, &p), s) in out.iter_mut().zip(phi).zip(salt) {
                    *o = self.coefficients_with(k, p, Some(s));
                }
            }
            None => {
                for (o, &p) in out.iter_mut().zip(phi) {
                    *o = self.coefficients_with(k, p, None);
                }
            }
        }
    }

    // F1 needs g0 only: no viscosity, conductivity nor saltation terms
    fn pressure_coefficient_batch(&self, phi: &[f64], out: &mut [f64]) {
        let a = self.g0.coefficient_a(self.friction);
        for (o, &p) in out.iter_mut().zip(phi) {
            let p = non_negative(p);
            *o = gd::f1(p, self.restitution, self.g0.g0_with_a(p, self.phi_max, a));
        }
    }

    fn drag_dissipation_factor(&self, cd_inf: f64, cd: f64) -> f64 {
        self.drag_dissipation.factor(cd_inf, cd)
    }

    fn saltation_enabled(&self) -> bool {
        self.saltation.enabled
    }

    #[inline]
    fn kinetic_pressure(&self, c: &KineticCoefficients, rho_p: f64, t: f64) -> f64 {
        rho_p * c.f1 * t
    }

    #[inline]
    fn shear_viscosity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        rho_p * d * c.f2 * sqrt_t
    }

    fn viscosity_coefficient(&self, tau: f64, gamma_dot: f64, rho_p: f64, d: f64, t: f64) -> f64 {
        tau / (rho_p * d * t.sqrt() * gamma_dot)
    }

    #[inline]
    fn conductivity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        rho_p * d * c.f3 * sqrt_t
    }

    #[inline]
    fn dissipation(&self, c: &KineticCoefficients, rho_p: f64, d: f64, t: f64) -> f64 {
        rho_p / d * c.f4 * t * t.sqrt()
    }

    #[inline]
    fn dissipation_per_temperature(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64 {
        rho_p / d * c.f4 * sqrt_t
    }

    // F1 = phi + 2 (1+e) phi^2 g0 is linear in g0 (table 1), so the g0 that gives the
    // measured F1 scales the closure's own by the ratio of the g0 parts; e is the bare
    // restitution of F1, never e_eff
    fn radial_distribution_of_pressure(&self, c: &KineticCoefficients, phi: f64, p: f64, rho_p: f64, t: f64) -> f64 {
        let f1 = p / (rho_p * t);
        c.g0 * (f1 - phi) / (c.f1 - phi)
    }

    fn radial_distribution_regressor(&self, phi: f64) -> f64 {
        self.g0.regressor(phi, self.phi_max)
    }

    fn saltation_input(&self, phi: f64, t: f64, beta: f64, rho_p: f64, d: f64) -> SaltationInput {
        SaltationInput { sqrt_t: t.sqrt(), k_drag: beta / (phi * (1.0 - phi)), particle_density: rho_p, diameter: d }
    }
}

#[typetag::serde(name = "frictional_collisional")]
impl GranularStress for FrictionalCollisional {
    fn as_kinetic(&self) -> Option<&dyn KineticTheory> {
        Some(self)
    }

    // the grains' restitution and friction are stated once, in [particles]; this model's
    // own keys override them for the continuum description only
    fn inherit(&mut self, given: &toml::Table, particles: &saltus_core::Grains) {
        if !given.contains_key("restitution") {
            self.restitution = particles.restitution;
        }
        if !given.contains_key("friction") {
            self.friction = particles.friction;
        }
    }
}

register_model!(Family::Granular, "frictional_collisional", GranularStress, FrictionalCollisional);

#[cfg(test)]
mod tests;
