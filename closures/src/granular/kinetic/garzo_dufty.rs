//! Garzo & Dufty (1999) kinetic-theory coefficients, as printed in the left column of
//! Chassagne et al. 2023 table 1, as pure functions of (phi, e, g0).
//!
//! # What is implemented
//!
//! With p = rho_p F1 T, eta = rho_p d F2 sqrt(T), kappa = rho_p d F3 sqrt(T) and
//! Gamma = rho_p / d F4 T^{3/2} (eqs 2.19-2.22, T = <v'^2>/3 in m^2/s^2):
//!
//! ```text
//! F1 = phi (1 + 2 (1+e) phi g0)
//! F2 = eta_k + eta_c + eta_b
//!   eta_k = (5 sqrt(pi)/96) [1 - 2/5 (1+e)(1-3e) phi g0] / ([1 - (1-e)^2/4 - 5/24 (1-e^2)] g0)
//!   eta_c = 4/5 (1+e) phi g0 eta_k
//!   eta_b = 4/(5 sqrt(pi)) (1+e) phi^2 g0
//! F3 = kappa_k + kappa_c + kappa_b
//!   kappa_k = (225 sqrt(pi)/576) [1 + 3/5 (1+e)^2 (2e-1) phi g0] / ([1 - 7/16 (1-e)] (1+e) g0)
//!   kappa_c = 6/5 (1+e) phi g0 kappa_k
//!   kappa_b = 2/sqrt(pi) (1+e) phi^2 g0
//! F4 = 12/sqrt(pi) (1-e^2) phi^2 g0
//! ```
//!
//! exactly as printed: no extra phi factor in eta_k / kappa_k and g0 in their
//! denominators. Check of that reading against Garzo & Dufty (1999) (GD, T in energy
//! units, m = rho_p pi d^3/6):
//!
//! * dilute viscosity eta_0 = 5/(16 d^2) sqrt(m T_E / pi) = (5 sqrt(pi)/96) rho_p d sqrt(T):
//!   the prefactor of eta_k, independent of phi as the Chapman-Enskog dilute viscosity must
//!   be; GD's eta_k*/eta_0 = [1 - 2/5 (1+e)(1-3e) phi chi] / (nu_eta* - zeta*/2) with
//!   nu_eta* = chi (3-e)(1+e)/4 = chi [1 - (1-e)^2/4] and zeta* = 5/12 chi (1-e^2): the
//!   printed denominator, g0 = chi included.
//! * eta_b is 3/5 of GD's bulk viscosity gamma* eta_0 = 128/(5 pi) phi^2 chi (1+e) eta_0
//!   = 4/(3 sqrt(pi)) (1+e) phi^2 g0 rho_p d sqrt(T) (docs/verification.md).
//! * dilute conductivity (for q = -kappa grad T with T in m^2/s^2)
//!   kappa_0 = m 75/(64 d^2) sqrt(T_E/(pi m)) = (75 sqrt(pi)/384) rho_p d sqrt(T);
//!   GD's kappa_k*/kappa_0 = 2/3 [..]/(nu_kappa* - 2 zeta*) with
//!   nu_kappa* - 2 zeta* = chi (1+e)/3 [1 - 7/16 (1-e)], i.e.
//!   kappa_k = 2 kappa_0 [..]/((1+e)[1 - 7/16 (1-e)] g0), and 2 x 75/384 = 225/576.
//!   7/16 is computed in floating point (`7.0 / 16.0`).
//! * kappa_b = 256/(25 pi) phi^2 chi (1+e) kappa_0 = 2/sqrt(pi) (1+e) phi^2 g0.
//! * F4: Gamma = 12 (1-e^2) rho_p phi^2 g0 T^{3/2} / (sqrt(pi) d), the Haff cooling rate
//!   (docs/verification.md, benchmark 7).
//!
//! These are consistent with eta = rho_p d F2 sqrt(T); tests check the dilute elastic
//! limits 5 sqrt(pi)/96 and 75 sqrt(pi)/384 and benchmarks 7 (Haff) and 8 (simple shear).
//! The c* (second Sonine) corrections of GD are not in table 1 and not implemented.
//!
//! # Infinite g0
//!
//! g0 = +inf (phi >= phi_max) is a valid input: every function returns its limit and never
//! NaN. Products "0 x g0" with an exactly-zero coefficient are taken as 0, the kinetic parts
//! eta_k, kappa_k are evaluated as (1/g0 - q phi)/D (finite limit), and F2, F3 are summed in
//! the form A + B/g0 + C g0 with C > 0 for e in [0, 1], so they tend to +inf.

/// sqrt(pi)
pub const SQRT_PI: f64 = 1.772_453_850_905_516;

/// Dilute viscosity prefactor 5 sqrt(pi)/96 (eta_0 / (rho_p d sqrt(T))).
pub const ETA_0: f64 = 5.0 * SQRT_PI / 96.0;

/// Conductivity prefactor 225 sqrt(pi)/576 = 2 kappa_0 / (rho_p d sqrt(T)).
pub const KAPPA_0: f64 = 225.0 * SQRT_PI / 576.0;

/// `a * g0`, with an exactly-zero coefficient annihilating an infinite g0.
#[inline]
fn times_g0(a: f64, g0: f64) -> f64 {
    if a == 0.0 {
        0.0
    } else {
        a * g0
    }
}

/// Denominator of eta_k without g0: 1 - (1-e)^2/4 - 5/24 (1-e^2).
#[inline]
fn eta_denominator(e: f64) -> f64 {
    1.0 - 0.25 * (1.0 - e) * (1.0 - e) - 5.0 / 24.0 * (1.0 - e * e)
}

/// q of eta_k's numerator 1 - q phi g0: 2/5 (1+e)(1-3e).
#[inline]
fn eta_q(e: f64) -> f64 {
    0.4 * (1.0 + e) * (1.0 - 3.0 * e)
}

/// Denominator of kappa_k without g0: (1 - 7/16 (1-e)) (1+e).
#[inline]
fn kappa_denominator(e: f64) -> f64 {
    (1.0 - 7.0 / 16.0 * (1.0 - e)) * (1.0 + e)
}

/// r of kappa_k's numerator 1 + r phi g0: 3/5 (1+e)^2 (2e-1).
#[inline]
fn kappa_r(e: f64) -> f64 {
    0.6 * (1.0 + e) * (1.0 + e) * (2.0 * e - 1.0)
}

/// Pressure coefficient F1 = phi (1 + 2 (1+e) phi g0).
#[inline]
pub fn f1(phi: f64, e: f64, g0: f64) -> f64 {
    phi + times_g0(2.0 * (1.0 + e) * phi * phi, g0)
}

/// Dissipation coefficient F4 = 12/sqrt(pi) (1 - e^2) phi^2 g0 (pass e_eff for F4').
#[inline]
pub fn f4(phi: f64, e: f64, g0: f64) -> f64 {
    times_g0(12.0 / SQRT_PI * (1.0 - e * e) * phi * phi, g0)
}

/// Kinetic viscosity eta_k* (finite limit -ETA_0 q phi / D as g0 -> inf).
#[inline]
pub fn eta_k(phi: f64, e: f64, g0: f64) -> f64 {
    ETA_0 * (1.0 / g0 - eta_q(e) * phi) / eta_denominator(e)
}

/// Collisional viscosity eta_c* = 4/5 (1+e) phi g0 eta_k*.
#[inline]
pub fn eta_c(phi: f64, e: f64, g0: f64) -> f64 {
    0.8 * (1.0 + e) * phi * ETA_0 * (1.0 - times_g0(eta_q(e) * phi, g0)) / eta_denominator(e)
}

/// Bulk share eta_b* = 4/(5 sqrt(pi)) (1+e) phi^2 g0 (3/5 of the bulk viscosity).
#[inline]
pub fn eta_b(phi: f64, e: f64, g0: f64) -> f64 {
    times_g0(0.8 / SQRT_PI * (1.0 + e) * phi * phi, g0)
}

/// eta_c* + eta_b*, summed without inf - inf: A + C g0.
#[inline]
pub fn eta_cb(phi: f64, e: f64, g0: f64) -> f64 {
    let s = 0.8 * (1.0 + e) * phi;
    let d = eta_denominator(e);
    let c = 0.8 / SQRT_PI * (1.0 + e) * phi * phi - ETA_0 * s * eta_q(e) * phi / d;
    ETA_0 * s / d + times_g0(c, g0)
}

/// Viscosity coefficient F2 = eta_k* + eta_c* + eta_b* (no saltation).
#[inline]
pub fn f2(phi: f64, e: f64, g0: f64) -> f64 {
    eta_k(phi, e, g0) + eta_cb(phi, e, g0)
}

/// Kinetic conductivity kappa_k* (finite limit KAPPA_0 r phi / D as g0 -> inf).
#[inline]
pub fn kappa_k(phi: f64, e: f64, g0: f64) -> f64 {
    KAPPA_0 * (1.0 / g0 + kappa_r(e) * phi) / kappa_denominator(e)
}

/// Collisional conductivity kappa_c* = 6/5 (1+e) phi g0 kappa_k*.
#[inline]
pub fn kappa_c(phi: f64, e: f64, g0: f64) -> f64 {
    1.2 * (1.0 + e) * phi * KAPPA_0 * (1.0 + times_g0(kappa_r(e) * phi, g0)) / kappa_denominator(e)
}

/// Bulk conductivity kappa_b* = 2/sqrt(pi) (1+e) phi^2 g0.
#[inline]
pub fn kappa_b(phi: f64, e: f64, g0: f64) -> f64 {
    times_g0(2.0 / SQRT_PI * (1.0 + e) * phi * phi, g0)
}

/// kappa_c* + kappa_b*, summed without inf - inf: A + C g0.
#[inline]
pub fn kappa_cb(phi: f64, e: f64, g0: f64) -> f64 {
    let s = 1.2 * (1.0 + e) * phi;
    let d = kappa_denominator(e);
    let c = 2.0 / SQRT_PI * (1.0 + e) * phi * phi + KAPPA_0 * s * kappa_r(e) * phi / d;
    KAPPA_0 * s / d + times_g0(c, g0)
}

/// Conductivity coefficient F3 = kappa_k* + kappa_c* + kappa_b* (no saltation).
#[inline]
pub fn f3(phi: f64, e: f64, g0: f64) -> f64 {
    kappa_k(phi, e, g0) + kappa_cb(phi, e, g0)
}

#[cfg(test)]
mod tests {
    use super::super::radial_distribution::chialvo_sundaresan;
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn dilute_elastic_limits_are_chapman_enskog() {
        // eta_0 = 5/(16 d^2) sqrt(m T/pi), kappa_0 = 75/(64 d^2) sqrt(T/(pi m)) (energy T):
        // in rho_p d sqrt(T) units 5 sqrt(pi)/96 and 75 sqrt(pi)/384.
        let pi = std::f64::consts::PI;
        assert_relative_eq!(f2(0.0, 1.0, 1.0), 5.0 * pi.sqrt() / 96.0, max_relative = 1e-15);
        assert_relative_eq!(f3(0.0, 1.0, 1.0), 75.0 * pi.sqrt() / 384.0, max_relative = 1e-15);
        assert_relative_eq!(SQRT_PI, pi.sqrt(), max_relative = 1e-16);
    }

    #[test]
    fn seven_sixteenths_is_floating_point() {
        // e = 0: denominator (1 - 7/16)(1 + 0) = 9/16, not 1 (integer 7/16 = 0).
        assert_relative_eq!(kappa_k(0.0, 0.0, 1.0), KAPPA_0 * 16.0 / 9.0, max_relative = 1e-15);
    }

    #[test]
    fn f4_vanishes_for_elastic_particles() {
        for phi in [0.0, 0.1, 0.5, 0.63] {
            let g0 = chialvo_sundaresan(phi, 0.635, 0.58);
            assert_eq!(f4(phi, 1.0, g0), 0.0);
        }
        assert_eq!(f4(0.7, 1.0, f64::INFINITY), 0.0);
    }

    #[test]
    fn bulk_viscosity_share_is_three_fifths() {
        let (phi, e, g0) = (0.4, 0.7, 3.0);
        let bulk = 4.0 / (3.0 * SQRT_PI) * (1.0 + e) * phi * phi * g0;
        assert_relative_eq!(eta_b(phi, e, g0), 0.6 * bulk, max_relative = 1e-15);
    }

    #[test]
    fn infinite_g0_gives_limits_never_nan() {
        for e in [0.0, 0.1, 1.0 / 3.0, 0.5, 0.7, 1.0] {
            for phi in [0.0, 0.1, 0.635, 0.9] {
                let g = f64::INFINITY;
                let vals = [
                    f1(phi, e, g),
                    f2(phi, e, g),
                    f3(phi, e, g),
                    f4(phi, e, g),
                    eta_k(phi, e, g),
                    eta_c(phi, e, g),
                    eta_b(phi, e, g),
                    kappa_k(phi, e, g),
                    kappa_c(phi, e, g),
                    kappa_b(phi, e, g),
                ];
                assert!(vals.iter().all(|v| !v.is_nan()), "e = {e}, phi = {phi}: {vals:?}");
                if phi > 0.0 {
                    assert_eq!(f1(phi, e, g), f64::INFINITY);
                    assert_eq!(f2(phi, e, g), f64::INFINITY, "e = {e}");
                    assert_eq!(f3(phi, e, g), f64::INFINITY, "e = {e}");
                }
            }
        }
    }

    proptest! {
        #[test]
        fn sums_equal_their_parts(phi in 0.0f64..0.63, e in 0.01f64..1.0) {
            let g0 = chialvo_sundaresan(phi, 0.635, 0.58);
            let f2_parts = eta_k(phi, e, g0) + eta_c(phi, e, g0) + eta_b(phi, e, g0);
            let f3_parts = kappa_k(phi, e, g0) + kappa_c(phi, e, g0) + kappa_b(phi, e, g0);
            prop_assert!((f2(phi, e, g0) - f2_parts).abs() <= 1e-12 * f2_parts.abs().max(1.0));
            prop_assert!((f3(phi, e, g0) - f3_parts).abs() <= 1e-12 * f3_parts.abs().max(1.0));
            // printed forms with g0 in the denominators
            let ek = ETA_0 * (1.0 - 0.4 * (1.0 + e) * (1.0 - 3.0 * e) * phi * g0)
                / ((1.0 - 0.25 * (1.0 - e).powi(2) - 5.0 / 24.0 * (1.0 - e * e)) * g0);
            let kk = KAPPA_0 * (1.0 + 0.6 * (1.0 + e).powi(2) * (2.0 * e - 1.0) * phi * g0)
                / ((1.0 - 7.0 / 16.0 * (1.0 - e)) * (1.0 + e) * g0);
            prop_assert!((eta_k(phi, e, g0) - ek).abs() <= 1e-12 * ek.abs().max(1e-3));
            prop_assert!((kappa_k(phi, e, g0) - kk).abs() <= 1e-12 * kk.abs().max(1e-3));
            prop_assert!((eta_c(phi, e, g0) - 0.8 * (1.0 + e) * phi * g0 * ek).abs() <= 1e-12 * ek.abs().max(1.0) * g0);
            prop_assert!((kappa_c(phi, e, g0) - 1.2 * (1.0 + e) * phi * g0 * kk).abs() <= 1e-12 * kk.abs().max(1.0) * g0);
        }

        #[test]
        fn positive_coefficients(phi in 1e-6f64..0.634, e in 0.0f64..1.0) {
            let g0 = chialvo_sundaresan(phi, 0.635, 3.7);
            prop_assert!(f1(phi, e, g0) > 0.0);
            prop_assert!(f2(phi, e, g0) > 0.0);
            prop_assert!(f3(phi, e, g0) > 0.0);
            prop_assert!(f4(phi, e, g0) >= 0.0);
        }
    }
}
