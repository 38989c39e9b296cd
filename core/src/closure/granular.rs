//! Granular stress: local rheologies (mu(I), mu(K)) and frictional-collisional kinetic
//! theory (Johnson-Jackson elastic stress + Garzo-Dufty kinetic theory).

use crate::needs::{Field, Needs};
use crate::param::Describe;

/// Local state from which a local rheology computes its control number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalState {
    /// |d v_x / dz| (1/s)
    pub shear_rate: f64,
    /// particle pressure p_p (Pa)
    pub pressure: f64,
    /// particle diameter (m)
    pub diameter: f64,
    /// particle density (kg/m^3)
    pub particle_density: f64,
    /// fluid dynamic viscosity (Pa s)
    pub fluid_viscosity: f64,
}

impl LocalState {
    /// `value` of a number that scales as 1/p (or 1/sqrt(p)) with the shear rate: zero
    /// without shear, +inf when sheared at zero pressure, `value(|gamma_dot|)` otherwise.
    fn at_positive_pressure(&self, value: impl FnOnce(f64) -> f64) -> f64 {
        let gamma = self.shear_rate.abs();
        if gamma == 0.0 {
            0.0
        } else if self.pressure <= 0.0 {
            f64::INFINITY
        } else {
            value(gamma)
        }
    }

    /// Inertial number I = d |gamma_dot| / sqrt(p / rho_p) (Chassagne 2023 section 1,
    /// Fry 2024 eq 34).
    pub fn inertial_number(&self) -> f64 {
        self.at_positive_pressure(|g| self.diameter * g * (self.particle_density / self.pressure).sqrt())
    }

    /// Viscous number J = eta_f |gamma_dot| / p (Fry 2024 eq 35).
    pub fn viscous_number(&self) -> f64 {
        self.at_positive_pressure(|g| self.fluid_viscosity * g / self.pressure)
    }
}

/// A local rheology: friction coefficient mu = tau_p / p_p and volume fraction as functions
/// of one dimensionless control number (I or K).
pub trait LocalRheology: Send + Sync {
    /// Name of the control number, `i` or `k` (the CSV input name).
    fn control_name(&self) -> &'static str;
    /// Control number from the local state.
    fn control_number(&self, s: &LocalState) -> f64;
    /// Friction coefficient at control number `x >= 0`.
    fn friction(&self, x: f64) -> f64;
    /// Volume fraction at control number `x >= 0`.
    fn packing(&self, x: f64) -> f64;
    /// Inverse of [`LocalRheology::packing`]: the control number at which the packing law
    /// gives `phi`; 0 at or above `packing(0)` (jammed), +inf at `phi <= 0`. The Eulerian
    /// solver uses it for the shear-induced (dilatancy) pressure. The default bisects in
    /// log x, assuming `packing` decreasing; models with a closed form override it.
    fn control_of_packing(&self, phi: f64) -> f64 {
        if phi >= self.packing(0.0) {
            return 0.0;
        }
        if phi <= 0.0 || phi.is_nan() {
            return f64::INFINITY;
        }
        let (mut lo, mut hi) = (-30.0f64, 30.0f64);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.packing(mid.exp()) > phi {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (0.5 * (lo + hi)).exp()
    }
    /// Pressure at which [`LocalRheology::control_number`] of `s` (its own `pressure`
    /// ignored) equals `x > 0`: with the packing inverse, the shear-induced pressure
    /// p(phi, gamma_dot) of the dilatancy law. 0 when `s` is not sheared or `x` is
    /// infinite. The default bisects in log p (the control number decreases with p);
    /// models with a closed form override it.
    fn pressure_at(&self, s: &LocalState, x: f64) -> f64 {
        if s.shear_rate == 0.0 || x.is_infinite() {
            return 0.0;
        }
        if x <= 0.0 || x.is_nan() {
            return f64::INFINITY;
        }
        let at = |lp: f64| self.control_number(&LocalState { pressure: lp.exp(), ..*s });
        let (mut lo, mut hi) = (-60.0f64, 60.0f64);
        for _ in 0..120 {
            let mid = 0.5 * (lo + hi);
            if at(mid) > x {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (0.5 * (lo + hi)).exp()
    }
    /// Friction and packing over a slice.
    fn eval_batch(&self, x: &[f64], mu: &mut [f64], phi: &mut [f64]) {
        for ((m, p), &xi) in mu.iter_mut().zip(phi.iter_mut()).zip(x) {
            *m = self.friction(xi);
            *p = self.packing(xi);
        }
    }
    /// Control numbers of a slice of states. The Eulerian solver calls it once per column
    /// evaluation (the face states of the shear stress), then [`LocalRheology::eval_batch`].
    fn control_number_batch(&self, s: &[LocalState], out: &mut [f64]) {
        for (o, st) in out.iter_mut().zip(s) {
            *o = self.control_number(st);
        }
    }
    /// [`LocalRheology::control_of_packing`] over a slice.
    fn control_of_packing_batch(&self, phi: &[f64], out: &mut [f64]) {
        for (o, &p) in out.iter_mut().zip(phi) {
            *o = self.control_of_packing(p);
        }
    }
    /// [`LocalRheology::pressure_at`] over slices of states and control numbers.
    fn pressure_at_batch(&self, s: &[LocalState], x: &[f64], out: &mut [f64]) {
        for ((o, st), &xi) in out.iter_mut().zip(s).zip(x) {
            *o = self.pressure_at(st, xi);
        }
    }
}

/// Johnson & Jackson (1987) enduring-contact (elastic) pressure, Chassagne et al. 2023
/// eq 2.14: p_el = P0 (phi - phi_rlp)^3 / (phi_max - phi)^5 for phi >= phi_rlp, 0 below,
/// +inf at or above phi_max. One definition for the kinetic closure and for the elastic
/// part the Eulerian solver gives local rheologies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JohnsonJacksonElastic {
    /// P0 (Pa)
    pub p0: f64,
    /// random loose packing where the pressure starts
    pub phi_rlp: f64,
    /// packing where it diverges
    pub phi_max: f64,
}

impl JohnsonJacksonElastic {
    /// `law(phi - phi_rlp, phi_max - phi)` between the two packings, 0 below phi_rlp and
    /// +inf at or above phi_max: the range of the pressure and of its derivative.
    #[inline]
    fn between_packings(&self, phi: f64, law: impl FnOnce(f64, f64) -> f64) -> f64 {
        if phi < self.phi_rlp {
            0.0
        } else if phi >= self.phi_max {
            f64::INFINITY
        } else {
            law(phi - self.phi_rlp, self.phi_max - phi)
        }
    }
    /// p_el(phi) (Pa)
    #[inline]
    pub fn pressure(&self, phi: f64) -> f64 {
        self.between_packings(phi, |a, b| self.p0 * a * a * a / b.powi(5))
    }
    /// dp_el/dphi = P0 (phi-phi_rlp)^2 / (phi_max-phi)^6 [3 (phi_max-phi) + 5 (phi-phi_rlp)] (Pa)
    #[inline]
    pub fn derivative(&self, phi: f64) -> f64 {
        self.between_packings(phi, |a, b| self.p0 * a * a * (3.0 * b + 5.0 * a) / b.powi(6))
    }
}

/// Dimensionless kinetic-theory coefficients at one volume fraction (Chassagne 2023 eqs
/// 2.19-2.22 and table 1): p = rho_p F1 T, eta = rho_p d F2 sqrt(T),
/// kappa = rho_p d F3 sqrt(T), Gamma = rho_p / d F4 T^{3/2}.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KineticCoefficients {
    /// radial distribution function at contact
    pub g0: f64,
    /// pressure coefficient
    pub f1: f64,
    /// viscosity coefficient (saltation-corrected when saltation is on and its input given)
    pub f2: f64,
    /// conductivity coefficient (idem)
    pub f3: f64,
    /// collisional dissipation coefficient (uses the effective restitution)
    pub f4: f64,
    /// effective restitution coefficient used in F4
    pub e_eff: f64,
}

/// Per-point input of the saltation correction (Chassagne 2023 eq 3.6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaltationInput {
    /// sqrt of the granular temperature (m/s)
    pub sqrt_t: f64,
    /// drag coefficient K of eq 2.10 (kg m^-3 s^-1)
    pub k_drag: f64,
    /// particle density (kg/m^3)
    pub particle_density: f64,
    /// particle diameter (m)
    pub diameter: f64,
}

/// Frictional-collisional stress: elastic (Johnson-Jackson) + kinetic theory.
pub trait KineticTheory: Send + Sync {
    /// Maximum packing fraction phi_max at which g0 and the elastic pressure diverge.
    fn phi_max(&self) -> f64;
    /// The Johnson-Jackson elastic law of eq 2.14 (the solver evaluates it inline).
    fn elastic_law(&self) -> JohnsonJacksonElastic;
    /// Johnson-Jackson elastic pressure p_el(phi) (Pa), eq 2.14.
    fn elastic_pressure(&self, phi: f64) -> f64;
    /// Derivative d p_el / d phi (Pa), for implicit treatment of the elastic pressure.
    fn elastic_pressure_derivative(&self, phi: f64) -> f64;
    /// Static friction coefficient mu_s of the Coulomb elastic shear stress, eq 2.15.
    fn static_friction(&self) -> f64;
    /// Coefficients at `phi`; with `salt = Some(..)` and saltation enabled, F2 and F3 carry
    /// the saltation correction of eqs 3.7 and 3.10.
    fn coefficients(&self, phi: f64, salt: Option<&SaltationInput>) -> KineticCoefficients;
    /// Factor c_J of the drag dissipation J_int = -phi (1-phi) K c_J T (eq 2.25: 3;
    /// eq 3.13: 3 + 2 C_D^inf / C_D).
    fn drag_dissipation_factor(&self, cd_inf: f64, cd: f64) -> f64;
    /// Whether the saltation correction is on.
    fn saltation_enabled(&self) -> bool;

    /// Kinetic-collisional pressure p_kin = rho_p F1 T (Pa) of the coefficients `c` at
    /// temperature `t` (m^2/s^2) for grains of density `rho_p`, Chassagne et al. 2023
    /// eq 2.19.
    fn kinetic_pressure(&self, c: &KineticCoefficients, rho_p: f64, t: f64) -> f64;
    /// Kinetic shear viscosity eta_kin = rho_p d F2 sqrt(T) (Pa s) of the coefficients `c`
    /// for grains of density `rho_p` and diameter `d` at sqrt(T) = `sqrt_t`, Chassagne et
    /// al. 2023 eq 2.20.
    fn shear_viscosity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64;
    /// F2 of a sheared state, eq 2.20 read backwards with eta_kin = tau / gamma_dot: the
    /// shear stress `tau` (Pa) at shear rate `gamma_dot` (1/s) and temperature `t` gives
    /// tau / (rho_p d sqrt(T) gamma_dot), the measured dimensionless viscosity.
    fn viscosity_coefficient(&self, tau: f64, gamma_dot: f64, rho_p: f64, d: f64, t: f64) -> f64;
    /// Conductivity kappa = rho_p d F3 sqrt(T) (kg m^-1 s^-1) of the heat flux
    /// q = -kappa dT/dz, Chassagne et al. 2023 eqs 2.18 and 2.21.
    fn conductivity(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64;
    /// Collisional dissipation Gamma = rho_p / d F4 T^{3/2} (W/m^3) at temperature `t`,
    /// Chassagne et al. 2023 eq 2.22 (F4' of table 1 with the effective restitution).
    fn dissipation(&self, c: &KineticCoefficients, rho_p: f64, d: f64, t: f64) -> f64;
    /// Gamma / T = rho_p / d F4 sqrt(T) (kg m^-3 s^-1) of eq 2.22: the sink that an
    /// implicit temperature step multiplies by the new T.
    fn dissipation_per_temperature(&self, c: &KineticCoefficients, rho_p: f64, d: f64, sqrt_t: f64) -> f64;
    /// Radial distribution g0 of a measured pressure `p` (Pa) at `phi` and temperature
    /// `t`, eq 2.19 read backwards (Chassagne et al. 2023 eq 3.1, which takes the total
    /// pressure for p_kin): the g0 at which the closure's F1, with its own restitution,
    /// equals p / (rho_p T). `c` are the closure's coefficients at `phi`.
    fn radial_distribution_of_pressure(&self, c: &KineticCoefficients, phi: f64, p: f64, rho_p: f64, t: f64) -> f64;
    /// Regressor x(phi) = phi^2 / (phi_max - phi)^{3/2} of the friction term of
    /// Chassagne et al. 2023 eq 3.2, g0 = g0_CS + a x, with the closure's phi_max: the
    /// variable against which a measured g0 - g0_CS gives the coefficient a(mu_p).
    fn radial_distribution_regressor(&self, phi: f64) -> f64;
    /// Saltation input (eq 3.6) of a cell of volume fraction `phi`, temperature `t` and
    /// drag friction `beta` (kg m^-3 s^-1), with K of eq 2.10 from the drag force of
    /// eq 2.9, beta = phi (1 - phi) K.
    fn saltation_input(&self, phi: f64, t: f64, beta: f64, rho_p: f64, d: f64) -> SaltationInput;

    /// [`KineticTheory::drag_dissipation_factor`] over a slice of C_D. The Eulerian solver
    /// calls it once per temperature step.
    fn drag_dissipation_batch(&self, cd_inf: f64, cd: &[f64], out: &mut [f64]) {
        for (o, &c) in out.iter_mut().zip(cd) {
            *o = self.drag_dissipation_factor(cd_inf, c);
        }
    }

    /// F1 of [`KineticTheory::coefficients`] alone over a slice of volume fractions: the
    /// Eulerian solver differences it in phi for the slope of the pressure, which needs
    /// none of the other coefficients.
    fn pressure_coefficient_batch(&self, phi: &[f64], out: &mut [f64]) {
        for (o, &p) in out.iter_mut().zip(phi) {
            *o = self.coefficients(p, None).f1;
        }
    }

    /// Coefficients over a slice of volume fractions, with the saltation input of each
    /// point (`None`: saltation off). The Eulerian solver calls it once per column.
    fn coefficients_batch(&self, phi: &[f64], salt: Option<&[SaltationInput]>, out: &mut [KineticCoefficients]) {
        match salt {
            Some(salt) => {
                for ((o, &p), s) in out.iter_mut().zip(phi).zip(salt) {
                    *o = self.coefficients(p, Some(s));
                }
            }
            None => {
                for (o, &p) in out.iter_mut().zip(phi) {
                    *o = self.coefficients(p, None);
                }
            }
        }
    }
}

/// The grain properties of `[particles]` that a granular closure may take as its defaults
/// ([`GranularStress::inherit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grains {
    /// diameter d (m)
    pub diameter: f64,
    /// density rho_p (kg/m^3)
    pub density: f64,
    /// normal restitution coefficient e
    pub restitution: f64,
    /// interparticle friction coefficient mu_p
    pub friction: f64,
}

/// A granular stress closure: exactly one of [`GranularStress::as_local`] and
/// [`GranularStress::as_kinetic`] returns `Some`.
#[typetag::serde(tag = "type")]
pub trait GranularStress: Describe + Send + Sync + std::fmt::Debug {
    /// Local-rheology view, if this is one.
    fn as_local(&self) -> Option<&dyn LocalRheology> {
        None
    }
    /// Kinetic-theory view, if this is one.
    fn as_kinetic(&self) -> Option<&dyn KineticTheory> {
        None
    }
    /// Take the grain properties this closure does not set itself from `[particles]`;
    /// `given` is the closure's own table, to tell a key set from a default. Called once
    /// at load, before the range check, so that the resolved scene shows the values used.
    fn inherit(&mut self, _given: &toml::Table, _grains: &Grains) {}
    /// Fields this closure makes available to others (granular temperature for kinetic
    /// theory).
    fn provides(&self) -> Needs {
        if self.as_kinetic().is_some() {
            Needs::of(&[Field::GranularTemperature])
        } else {
            Needs::NONE
        }
    }
}
