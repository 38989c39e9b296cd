//! Unit and property tests of [`super::KOmega`] (Cheng et al. eqs 21-35, table 1).

use super::*;
use approx::assert_relative_eq;
use proptest::prelude::*;

const NU: f64 = 1e-6;

fn terms_of(m: &KOmega, cells: &[(f64, f64, f64, f64, f64, f64)]) -> TwoEquationTerms {
    // (phi, dudz, k, omega, beta, dphidz)
    let n = cells.len();
    let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * 1e-3).collect();
    let dz = vec![1e-3; n];
    let phi: Vec<f64> = cells.iter().map(|c| c.0).collect();
    let dudz: Vec<f64> = cells.iter().map(|c| c.1).collect();
    let k: Vec<f64> = cells.iter().map(|c| c.2).collect();
    let w: Vec<f64> = cells.iter().map(|c| c.3).collect();
    let beta: Vec<f64> = cells.iter().map(|c| c.4).collect();
    let dphidz: Vec<f64> = cells.iter().map(|c| c.5).collect();
    let tr = [k.as_slice(), w.as_slice()];
    let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 3e-3, nu_f: NU, transported: &tr };
    let input = TwoEquationInput {
        col,
        drag: &beta,
        dphidz: &dphidz,
        fluid_density: 1000.0,
        particle_density: 1192.0,
        gravity_normal: 9.81,
        friction_velocity: 0.05,
    };
    let mut out = TwoEquationTerms::new(n);
    m.terms(&input, &mut out);
    out
}

#[test]
fn defaults_are_table_1() {
    let m = KOmega::default();
    assert_eq!(
        [m.alpha_0, m.alpha_star_0, m.re_k, m.re_omega, m.re_beta, m.c_mu, m.sigma_k, m.sigma_omega],
        [1.0 / 9.0, 0.024, 6.0, 2.95, 8.0, 0.09, 2.0, 2.0]
    );
    // C_s: recalibrated from table 1's 1 on the Revil-Baudard sheet flow (see the decisions)
    assert_eq!([m.c_s, m.c_1omega, m.c_2omega, m.c_3omega, m.c_4omega], [0.25, 0.52, 0.072, 0.14, 0.0]);
    // K_r: recalibrated from the paper's 80 for the low-Re functions (see the decisions)
    assert_eq!([m.roughness, m.k_r, m.phi_bed], [2.5, 65.0, 0.55]);
    // eq 24's time average of the relative velocity: off unless a scene asks (the DEM's)
    assert_eq!(m.slip_average_start, None);
    assert_eq!(TwoEquation::slip_average_start(&m), None);
    let with = KOmega { slip_average_start: Some(5.0), ..KOmega::default() };
    assert_eq!(TwoEquation::slip_average_start(&with), Some(5.0));
    assert!(m.validate().is_ok());
}

#[test]
fn high_reynolds_limit_is_standard_wilcox() {
    // Re_t -> inf: alpha* -> 1, C_mu* -> C_mu, C_1w* -> C_1w (Cheng after eq 29)
    let m = KOmega::default();
    assert_relative_eq!(m.alpha_star(1e12), 1.0, max_relative = 1e-10);
    assert_relative_eq!(m.c_mu_star(1e12), 0.09, max_relative = 1e-12);
    assert_relative_eq!(m.c_1omega_star(1e12), 0.52, max_relative = 1e-10);
    assert_eq!(m.c_mu_star(f64::INFINITY), 0.09);
}

#[test]
fn low_reynolds_limit() {
    // Re_t -> 0: alpha* -> alpha*_0, C_mu* -> 4/15 C_mu, C_1w* -> C_1w alpha_0 / alpha*_0
    let m = KOmega::default();
    assert_eq!(m.alpha_star(0.0), 0.024);
    assert_relative_eq!(m.c_mu_star(0.0), 0.09 * 4.0 / 15.0, max_relative = 1e-14);
    assert_relative_eq!(m.c_1omega_star(0.0), 0.52 / 9.0 / 0.024, max_relative = 1e-14);
}

#[test]
fn s_r_is_continuous_at_ks_plus_5_and_tends_to_kr_over_ks() {
    let m = KOmega::default();
    assert_relative_eq!(m.s_r(5.0 - 1e-12), 1600.0, max_relative = 1e-9);
    assert_relative_eq!(m.s_r(5.0), 1600.0, max_relative = 1e-12);
    assert_relative_eq!(m.s_r(200.0), 65.0 / 200.0, max_relative = 1e-12);
    // Revil-Baudard: u* = 0.05, d = 3 mm: k_s+ = 375, omega_bed = 65/375 u*^2/nu
    assert_relative_eq!(m.omega_bed(0.05, NU, 3e-3), 65.0 / 375.0 * 2500.0, max_relative = 1e-12);
}

/// The rough wall and in-bed omega of eqs 32-35, evaluated by hand: the fixed bed of Revil-Baudard (case FB,
/// u* = 0.052 m/s, d = 3 mm, k_s = 2.5 d = 7.5 mm, nu = 1e-6): k_s+ = 390, fully rough,
/// S_r = K_r/k_s+ (the exponential is e^-385), omega_bed = S_r u*^2/nu = 65/390 * 2704
/// = 450.67 /s, imposed at the wall face; a transitional k_s+ = 10 (u* = 1/750 m/s) takes
/// the blend K_r/10 + ((200/10)^2 - K_r/10) e^-5; a smooth k_s+ = 2 (200/2)^2.
#[test]
fn rough_wall_omega_is_eqs_32_35() {
    let m = KOmega { wall: KOmegaWall::Rough, ..KOmega::default() };
    assert_relative_eq!(m.omega_bed(0.052, NU, 3e-3), 65.0 / 390.0 * 0.052 * 0.052 / NU, max_relative = 1e-12);
    assert_relative_eq!(m.omega_bed(0.052, NU, 3e-3), 450.6667, max_relative = 1e-6);
    assert_eq!(m.wall_location(), WallOmega::WallFace);
    // the wall value does not depend on the first-cell distance: it is imposed at the face
    assert_eq!(m.wall_omega(1e-6, 0.052, NU, 3e-3), m.wall_omega(1e-3, 0.052, NU, 3e-3));
    assert_relative_eq!(m.wall_omega(1e-4, 0.052, NU, 3e-3), 450.6667, max_relative = 1e-6);
    let u = 10.0 * NU / 7.5e-3;
    let s_r = 6.5 + (400.0 - 6.5) * (-5.0f64).exp();
    assert_relative_eq!(m.omega_bed(u, NU, 3e-3), s_r * u * u / NU, max_relative = 1e-12);
    let u = 2.0 * NU / 7.5e-3;
    assert_relative_eq!(m.omega_bed(u, NU, 3e-3), 1e4 * u * u / NU, max_relative = 1e-12);
    // eq 35's smooth branch makes omega_bed = 40000 nu / k_s^2 whatever u*: a bed without
    // shear (u* = 0, or 1e-308) has that limit, finite, not 0 x inf
    let limit = 40000.0 * NU / (7.5e-3 * 7.5e-3);
    for u in [0.0, 1e-308, 1e-12, u] {
        assert_relative_eq!(m.omega_bed(u, NU, 3e-3), limit, max_relative = 1e-12);
    }
    // eq 32: the step at phi_b = 0.55, (tanh(500 (phi - phi_b)) + 1)/2
    assert_relative_eq!(m.gamma(0.55), 0.5, max_relative = 1e-15);
    assert_relative_eq!(m.gamma(0.56), 0.5 * (5.0f64.tanh() + 1.0), max_relative = 1e-15);
    // eqs 26 and 33 with drag in the bed: the relaxation still settles on Gamma omega_bed
    let t = terms_of(&m, &[(0.58, 0.0, 1e-6, 40.0, 5e4, 0.0)]);
    let steady = t.omega_source[0] / t.omega_sink[0];
    assert_relative_eq!(steady, m.gamma(0.58) * m.omega_bed(0.05, NU, 3e-3), max_relative = 1e-12);
    // roughness and K_r scale as eq 35 says: twice K_r, twice omega_bed when fully rough
    let m2 = KOmega { k_r: 130.0, ..m.clone() };
    assert_relative_eq!(m2.omega_bed(0.052, NU, 3e-3), 2.0 * m.omega_bed(0.052, NU, 3e-3), max_relative = 1e-12);
}

/// Start-up: outside the bed the uniform log-layer state, inside the packed bed k = 0 and
/// omega = omega_bed (nu_t = 0), the blend by Gamma of eq 32 in between; a column without
/// forcing keeps a finite omega in its bed.
#[test]
fn initial_state_is_damped_in_the_bed() {
    let m = KOmega::default();
    let (u, h) = (0.05, 0.168);
    let (k0, w0) = m.initial_state(u, h, NU);
    assert_relative_eq!(k0, 0.0025 / 0.3, max_relative = 1e-12);
    assert_eq!(m.initial_state_at(0.0, u, h, NU, 3e-3), (k0, w0));
    let (k, w) = m.initial_state_at(0.587, u, h, NU, 3e-3);
    assert!(k <= 1e-12 * k0, "{k}");
    assert_relative_eq!(w, m.omega_bed(u, NU, 3e-3), max_relative = 1e-9);
    assert!(m.nu_t(k, w, NU) <= 1e-12 * NU);
    let (k, w) = m.initial_state_at(0.55, u, h, NU, 3e-3);
    assert_relative_eq!(k, 0.5 * k0, max_relative = 1e-12);
    assert_relative_eq!(w, 0.5 * (w0 + m.omega_bed(u, NU, 3e-3)), max_relative = 1e-12);
    let (k, w) = m.initial_state_at(0.6, 0.0, h, NU, 3e-3);
    assert!(k >= 0.0 && w.is_finite() && w > 0.0);
}

#[test]
fn smooth_wall_blends_viscous_and_log_values() {
    let m = KOmega::default();
    let (z0, u) = (1e-5, 0.03);
    let vis = 6.0 * NU / (0.075 * z0 * z0);
    let log = u / (0.3 * 0.41 * z0);
    assert_relative_eq!(m.omega_smooth_wall(z0, u, NU), (vis * vis + log * log).sqrt(), max_relative = 1e-14);
    // deep in the viscous sublayer the viscous value dominates
    assert_relative_eq!(m.omega_smooth_wall(1e-7, u, NU), 6.0 * NU / (0.075 * 1e-14), max_relative = 1e-3);
}

#[test]
fn clear_fluid_terms_are_wilcox() {
    let m = KOmega::default();
    let (k, w, g) = (1e-3, 10.0, 5.0);
    let t = terms_of(&m, &[(0.0, g, k, w, 0.0, 0.0)]);
    let re_t = k / (NU * w);
    let nut = m.alpha_star(re_t) * k / w;
    assert_relative_eq!(t.k_source[0], nut * g * g, max_relative = 1e-14);
    assert_relative_eq!(t.k_sink[0], m.c_mu_star(re_t) * w, max_relative = 1e-14);
    assert_relative_eq!(t.omega_source[0], m.c_1omega_star(re_t) * w / k * nut * g * g, max_relative = 1e-12);
    assert_relative_eq!(t.omega_sink[0], 0.072 * w, max_relative = 1e-14);
    assert_relative_eq!(t.k_diffusivity[0], NU + nut / 2.0, max_relative = 1e-14);
}

#[test]
fn in_bed_relaxation_drives_omega_to_omega_bed() {
    // no shear, no drag, no gradient, inside the bed: the local balance
    // source = sink omega gives omega = omega_bed Gamma
    let m = KOmega::default();
    let w = 3.0;
    let t = terms_of(&m, &[(0.6, 0.0, 1e-6, w, 0.0, 0.0)]);
    let steady = t.omega_source[0] / t.omega_sink[0];
    assert_relative_eq!(steady, m.omega_bed(0.05, NU, 3e-3) * m.gamma(0.6), max_relative = 1e-12);
    assert!(m.gamma(0.6) > 1.0 - 1e-10 && m.gamma(0.0) < 1e-100);
}

/// The drag damping of eqs 21, 25 and 26 in a sheet-layer cell of the Revil-Baudard scene
/// (phi = 0.14, beta = 3.76e4 kg m^-3 s^-1, omega = 250 /s, no shear, no gradient), by
/// hand: t_p = rho_p/beta, t_l = C_t/(C_mu omega), St = t_p/t_l = 4.28, lambda =
/// exp(-C_s St); k sink = C_mu* omega + 2 beta (1 - lambda) phi/(rho_f (1 - phi)), omega
/// sink = C_2w omega + C_3w (the same drag rate).
#[test]
fn drag_damping_is_eqs_21_25_26() {
    for c_s in [0.3, 1.0] {
        let m = KOmega { c_s, ..KOmega::default() };
        let (phi, beta, w, k) = (0.14, 3.76e4, 250.0, 1e-3);
        let t = terms_of(&m, &[(phi, 0.0, k, w, beta, 0.0)]);
        let st = (1192.0 / beta) / ((1.0 / 6.0) / (0.09 * w));
        assert_relative_eq!(st, 4.2797, max_relative = 1e-4);
        let lambda = (-c_s * st).exp();
        assert_relative_eq!(m.lambda(beta, 1192.0, w), lambda, max_relative = 1e-12);
        let drag = 2.0 * beta * (1.0 - lambda) * phi / (1000.0 * (1.0 - phi));
        let re_t = k / (NU * w);
        assert_relative_eq!(t.k_sink[0], m.c_mu_star(re_t) * w + drag, max_relative = 1e-12);
        assert_relative_eq!(t.omega_sink[0], 0.072 * w + 0.14 * drag, max_relative = 1e-12);
        assert_eq!(t.k_source[0], 0.0);
    }
    // heavier damping with the table-1 C_s: lambda 0.014 against 0.28
    let (a, b) = (KOmega { c_s: 1.0, ..KOmega::default() }, KOmega::default());
    assert!(a.lambda(3.76e4, 1192.0, 250.0) < 0.02 && b.lambda(3.76e4, 1192.0, 250.0) > 0.25);
}

#[test]
fn stable_stratification_is_a_sink_of_k() {
    let m = KOmega::default();
    let a = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, 0.0)]);
    let b = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, -10.0)]);
    assert_eq!(a.k_source[0], b.k_source[0]);
    assert!(b.k_sink[0] > a.k_sink[0]);
    let c = terms_of(&m, &[(0.1, 5.0, 1e-3, 10.0, 0.0, 10.0)]);
    assert!(c.k_source[0] > a.k_source[0]);
    assert_eq!(c.k_sink[0], a.k_sink[0]);
}

#[test]
fn round_trip_and_unknown_keys() {
    let m: KOmega = toml::from_str("wall = \"rough\"\nc_3omega = 0.2").unwrap();
    assert_eq!(m.wall, KOmegaWall::Rough);
    assert_eq!(m.c_3omega, 0.2);
    assert!(toml::from_str::<KOmega>("c3 = 0.2").is_err());
    let bad = KOmega { sigma_k: 0.0, ..KOmega::default() };
    assert_eq!(bad.validate().unwrap_err().key, "sigma_k");
    let bad = KOmega { phi_bed: 1.0, ..KOmega::default() };
    assert_eq!(bad.validate().unwrap_err().key, "phi_bed");
}

#[test]
fn provides_and_transports_k_and_omega() {
    let m = KOmega::default();
    let p = m.provides();
    assert!(p.contains(Field::Tke) && p.contains(Field::Omega) && p.contains(Field::ReynoldsStress));
    assert_eq!(m.transported(), &["k", "omega"]);
    assert!(m.as_two_equation().is_some());
}

proptest! {
    #[test]
    fn damping_functions_are_bounded_and_monotone(a in 0.0f64..1e6, b in 0.0f64..1e6) {
        let m = KOmega::default();
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        prop_assert!(m.alpha_star(lo) <= m.alpha_star(hi) + 1e-15);
        prop_assert!(m.alpha_star(hi) >= 0.024 && m.alpha_star(hi) <= 1.0);
        prop_assert!(m.c_mu_star(lo) <= m.c_mu_star(hi) + 1e-15);
        prop_assert!(m.c_mu_star(hi) >= 0.024 - 1e-15 && m.c_mu_star(hi) <= 0.09 + 1e-15);
        prop_assert!(m.omega_production_factor(hi) >= 0.52 / 9.0 - 1e-15);
        prop_assert!(m.omega_production_factor(hi) <= 0.52 + 1e-15);
    }

    #[test]
    fn lambda_in_unit_interval_and_decreasing_in_response_time(
        beta in 1e-3f64..1e8, omega in 1e-3f64..1e5,
    ) {
        let m = KOmega::default();
        let l = m.lambda(beta, 1192.0, omega);
        prop_assert!((0.0..=1.0).contains(&l));
        // heavier drag = shorter response time = particles follow the eddies better
        prop_assert!(m.lambda(2.0 * beta, 1192.0, omega) >= l);
    }

    #[test]
    fn terms_are_non_negative_and_finite(
        cells in proptest::collection::vec(
            (0.0f64..0.64, -100.0f64..100.0, 0.0f64..1.0, 1e-3f64..1e6, 0.0f64..1e6, -500.0f64..500.0),
            1..40,
        ),
        c4 in 0.0f64..1.0,
    ) {
        let m = KOmega { c_4omega: c4, ..KOmega::default() };
        let t = terms_of(&m, &cells);
        for v in [&t.k_source, &t.k_sink, &t.k_diffusivity, &t.omega_source, &t.omega_sink, &t.omega_diffusivity] {
            for x in v.iter() {
                prop_assert!(x.is_finite() && *x >= 0.0, "{x}");
            }
        }
        for (d, _) in t.k_diffusivity.iter().zip(&cells) {
            prop_assert!(*d >= NU);
        }
    }

    #[test]
    fn eddy_viscosity_batch_is_eq_29(
        cells in proptest::collection::vec((0.0f64..1.0, 1e-3f64..1e4), 1..50),
    ) {
        let m = KOmega::default();
        let n = cells.len();
        let k: Vec<f64> = cells.iter().map(|c| c.0).collect();
        let w: Vec<f64> = cells.iter().map(|c| c.1).collect();
        let z = vec![0.0; n];
        let tr = [k.as_slice(), w.as_slice()];
        let col = ColumnView { z: &z, dz: &z, phi: &z, dudz: &z, diameter: 1e-3, nu_f: NU, transported: &tr };
        let mut out = vec![0.0; n];
        m.eddy_viscosity(&col, &mut out);
        for i in 0..n {
            let re = k[i] / (NU * w[i]);
            let a = (0.024 + re / 6.0) / (1.0 + re / 6.0);
            prop_assert!((out[i] - a * k[i] / w[i]).abs() <= 1e-12 * out[i].abs().max(1e-300));
            prop_assert!(out[i] <= k[i] / w[i] * (1.0 + 1e-12));
        }
    }
}

/// Eq 34's bed omega stays finite and positive over the roughness range for any grain from
/// 1e-6 m to 1 m and any u* up to 10 m/s (smooth limit included); a roughness outside
/// [1e-3, 1e3] d, where 40000 nu / k_s^2 can overflow, is refused by name.
#[test]
fn bed_omega_is_finite_over_the_roughness_range_and_beyond_it_refused() {
    for roughness in [1e-3, 1.0, 2.5, 1e3] {
        let m = KOmega { roughness, ..KOmega::default() };
        assert!(m.validate().is_ok());
        for d in [1e-6, 1e-3, 1.0] {
            for u_star in [0.0, 1e-308, 1e-3, 10.0] {
                let w = m.omega_bed(u_star, 1e-6, d);
                assert!(w.is_finite() && w > 0.0, "k_s {roughness} d, d {d}, u* {u_star}: {w}");
            }
        }
    }
    for roughness in [0.0, 1e-4, 1e-300, 1.1e3, f64::NAN, f64::INFINITY] {
        let bad = KOmega { roughness, ..KOmega::default() };
        assert_eq!(bad.validate().unwrap_err().key, "roughness", "{roughness}");
    }
}
