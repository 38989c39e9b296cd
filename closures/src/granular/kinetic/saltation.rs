//! Saltation correction of the kinetic viscosity and conductivity (Chassagne et al. 2023
//! section 3.4, after Jenkins, Cantat & Valance 2010).

use saltus_core::{Params, SaltationInput};
use serde::{Deserialize, Serialize};

/// Saltation viscosity and its harmonic combination with the kinetic part:
///
/// ```text
/// eta_salt*   = rho_p phi sqrt(T) / (c0 d K)                       (eq 3.6)
/// kappa_salt* = eta_salt* / sigma                                   (eq 3.9)
/// F2 = eta_salt* eta_k* / (eta_salt* + eta_k*) + eta_c* + eta_b*    (eq 3.7)
/// F3 = kappa_salt* kappa_k* / (kappa_salt* + kappa_k*) + kappa_c* + kappa_b*   (eq 3.10)
/// ```
///
/// * Defaults: `enabled = true`, `c0 = 5` (subaqueous DEM value; 20 for aeolian), and
///   `sigma = 0.5` (table 1 right column).
/// * Valid range: c0 > 0, sigma > 0.
/// * Decisions: the harmonic mean is evaluated as x_k s/(s + |x_k|), identical to the
///   paper for x_k > 0; Garzo-Dufty's eta_k* turns negative in dense flows for e < 1/3,
///   where the printed form would have a pole at s = -x_k; this form only shrinks it. K <= 0
///   (no drag) or d <= 0 gives eta_salt = +inf, i.e. no correction; sqrt(T) = 0 or phi = 0
///   gives eta_salt = 0 and removes the kinetic part.
/// * `saltation = { enabled = false }` switches it off (initial model).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Params)]
#[serde(deny_unknown_fields, default)]
pub struct Saltation {
    /// apply the correction
    pub enabled: bool,
    /// correlation constant c0 of eta_salt (eq 3.5)
    #[param(range = "(0, inf)", unit = "-")]
    pub c0: f64,
    /// eta_salt / kappa_salt (eq 3.9)
    #[param(range = "(0, inf)", unit = "-")]
    pub sigma: f64,
}

impl Default for Saltation {
    fn default() -> Self {
        Self { enabled: true, c0: 5.0, sigma: 0.5 }
    }
}

impl Saltation {
    /// Saltation switched off, parameters at their defaults.
    pub fn disabled() -> Self {
        Self { enabled: false, ..Self::default() }
    }

    /// eta_salt* of eq 3.6 at volume fraction `phi`.
    #[inline]
    pub fn eta_salt(&self, phi: f64, s: &SaltationInput) -> f64 {
        let den = self.c0 * s.diameter * s.k_drag;
        if den.is_nan() || den <= 0.0 {
            return f64::INFINITY;
        }
        s.particle_density * phi.max(0.0) * s.sqrt_t.max(0.0) / den
    }

    /// kappa_salt* of eq 3.9.
    #[inline]
    pub fn kappa_salt(&self, phi: f64, s: &SaltationInput) -> f64 {
        self.eta_salt(phi, s) / self.sigma
    }
}

/// Harmonic combination of a kinetic part `kinetic` with a saltation part `salt >= 0`:
/// kinetic salt / (salt + |kinetic|); `kinetic` when salt = +inf; 0 when both vanish.
#[inline]
pub fn harmonic(kinetic: f64, salt: f64) -> f64 {
    if salt.is_infinite() {
        return kinetic;
    }
    let den = salt + kinetic.abs();
    if den > 0.0 {
        kinetic * salt / den
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn input(k: f64) -> SaltationInput {
        SaltationInput { sqrt_t: 0.1, k_drag: k, particle_density: 2500.0, diameter: 6e-3 }
    }

    #[test]
    fn eta_salt_formula() {
        let s = Saltation::default();
        assert_relative_eq!(s.eta_salt(0.1, &input(1000.0)), 2500.0 * 0.1 * 0.1 / (5.0 * 6e-3 * 1000.0));
        assert_relative_eq!(s.kappa_salt(0.1, &input(1000.0)), 2.0 * s.eta_salt(0.1, &input(1000.0)));
        assert_eq!(s.eta_salt(0.1, &input(0.0)), f64::INFINITY);
    }

    #[test]
    fn harmonic_limits() {
        assert_eq!(harmonic(0.3, f64::INFINITY), 0.3);
        assert_relative_eq!(harmonic(0.3, 0.3), 0.15);
        assert_eq!(harmonic(0.3, 0.0), 0.0);
        assert_eq!(harmonic(0.0, 0.0), 0.0);
        assert!(harmonic(-0.3, 0.3) < 0.0 && harmonic(-0.3, 0.3) > -0.3);
        assert_relative_eq!(harmonic(0.3, 1e12), 0.3, max_relative = 1e-11);
    }
}
