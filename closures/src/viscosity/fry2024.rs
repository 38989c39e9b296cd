//! Fry et al. (2024) fluid-phase viscosity for weakly inertial bedload.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, EffectiveViscosity, Limit};
use serde::{Deserialize, Serialize};

/// Fry, Lacaze et al. (2024) apparent viscosity of the equivalent fluid phase in bedload
///
/// ```text
/// eta_eq / eta_f = (1 - phi)^(-beta),  beta = beta0 + a (r theta sqrt(Re_p))^(2/3)
/// nu_eff / nu_f  = (1 - phi)^(-beta - 1)
/// ```
///
/// * Source: Fry et al. 2024 eq 32 with the first form of eq 51 (fit of their IBM-DEM
///   Couette bedload simulations, figure 8).
/// * Why the extra power of (1 - phi): Fry's apparent viscosity is defined on the phase
///   stress, eta_eq = Sigma^f / gamma_dot (eq 50), and Sigma^f = eps `<sigma>^f` + n `<s^f>^p`
///   minus the Reynolds stress (eq 21) already carries the fluid fraction eps = 1 - phi. The fluid-phase
///   stress of this library's solvers is eps rho_f nu_eff du_f/dz (the trait's ratio
///   multiplies nu_f inside eps), so nu_eff = eta_eq / (rho_f eps): the fluid-phase stress
///   is then exactly eta_f (1 - phi)^(-beta) gamma_dot, eq 50 with eq 32.
/// * Defaults: `beta0 = 0.565`, `a = 0.85` (eq 51), and the flow's dimensionless numbers
///   `shields` theta = 0.67, `re_p` = 1 (Re_p = rho_f Gamma d^2 / eta_f with Gamma the
///   Couette shear rate far above the bed, *not* a slip Reynolds number), `density_ratio`
///   r = rho_p/rho_f = 2.5: the paper's reference case, giving beta = 1.7638 (their direct
///   fit of that case is 1.71).
/// * Valid range: `beta0` in [0, 10], `a` in [0, 10], `shields` in (0, 10], `re_p` in
///   (0, 1000], `density_ratio` in (1, 20]. The fit itself is only supported for
///   0.1 <= Re_p <= 10, 0.1 <= theta <= 0.7 and r = 2.5 (the paper warns it is not expected
///   to hold at large Re_p and theta); outside that the law is an extrapolation.
/// * Small-phi limit (eq 52): eta_eq / eta_f = 1 + beta phi = 1 + phi [beta0 + a (r theta
///   sqrt(Re_p))^(2/3)], *not* Einstein's 1 + 5/2 phi (beta0 = 0.565 is "quite smaller than
///   2.5"); nu_eff / nu_f = 1 + (beta + 1) phi.
/// * The flow numbers are scene parameters, not local fields: beta is constant over the
///   domain, as in the paper's fits. `phi_limit` = 1.
/// * In the DEM's unresolved column the exchange of each grain's drag, slice by slice,
///   already carries a stress across the grains (Fry's n <s^f>^p); the Couette case there
///   takes `clear_fluid` (docs/validation.md, Fry et al. 2024).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "fry2024",
    source = "Fry et al. 2024 eqs 32, 51 (first form), 52",
    equation = "nu_eff / nu_f = (1 - phi)^(-beta - 1): eps nu_eff / nu_f = (1 - phi)^(-beta), beta = beta0 + a (r theta sqrt(Re_p))^(2/3)",
    limits = [Limit::Dilute, Limit::Increasing]
)]
pub struct Fry2024 {
    /// viscous-limit exponent beta0
    #[param(range = "[0, 10]", unit = "-")]
    pub beta0: f64,
    /// prefactor of (r theta sqrt(Re_p))^(2/3)
    #[param(range = "[0, 10]", unit = "-")]
    pub a: f64,
    /// Shields number theta of the flow
    #[param(range = "(0, 10]", unit = "-")]
    pub shields: f64,
    /// shear particle Reynolds number rho_f Gamma d^2 / eta_f
    #[param(range = "(0, 1000]", unit = "-")]
    pub re_p: f64,
    /// density ratio r = rho_p / rho_f
    #[param(range = "(1, 20]", unit = "-")]
    pub density_ratio: f64,
}

impl Default for Fry2024 {
    fn default() -> Self {
        Self { beta0: 0.565, a: 0.85, shields: 0.67, re_p: 1.0, density_ratio: 2.5 }
    }
}

impl Fry2024 {
    /// Exponent beta of eq 51 (first form).
    #[inline]
    pub fn beta(&self) -> f64 {
        self.beta0 + self.a * (self.density_ratio * self.shields * self.re_p.sqrt()).powf(2.0 / 3.0)
    }
}

/// Apparent viscosity ratio eta_eq / eta_f of a fluid-phase stress measured in a DEM
/// column (Fry et al. 2024 eq 50 with eq 32), the quantity the exponent of eq 51 is fitted
/// on.
///
/// ```text
/// eta_eq / eta_f = (tau_f + beta gamma_f d^2 / 20) / (eta_f gamma_f)
/// ```
///
/// * `tau_f` is the column's own viscous stress eps eta_f du_f/dz, `gamma` the fluid's
///   shear rate du_f/dz, `eta_f` the fluid's dynamic viscosity.
/// * The second term is Fry's n<s^f>^p, the stress the drag exchange carries across each
///   grain when the drag is taken over the grain's volume: over a sphere of diameter `d`
///   in a linear shear the slip varies linearly, and the first moment of an exchange of
///   coefficient `beta` (`exchange`, per unit volume) is beta gamma_f d^2 / 20, since the
///   integral of (z - z_c)^2 over a sphere is V d^2 / 20.
/// * Not finite where the shear vanishes: the ratio is measured only in sheared cells.
/// * Valid for `d` and `eta_f` finite and > 0, `exchange` >= 0 and `gamma` != 0, all
///   finite; the DEM column's cells give them in SI units.
#[inline]
pub fn stress_ratio(tau_f: f64, exchange: f64, gamma: f64, d: f64, eta_f: f64) -> f64 {
    (tau_f + exchange * gamma * (d * d / 20.0)) / (eta_f * gamma)
}

/// (1 - phi)^(-beta - 1), shared by the scalar and the batch path so that both agree bitwise.
#[inline]
fn power_law(phi: f64, beta: f64) -> f64 {
    (1.0 - phi).powf(-beta - 1.0)
}

#[typetag::serde(name = "fry2024")]
impl EffectiveViscosity for Fry2024 {
    #[inline]
    fn ratio(&self, phi: f64) -> f64 {
        power_law(phi, self.beta())
    }
    fn ratio_batch(&self, phi: &[f64], out: &mut [f64]) {
        let beta = self.beta();
        for (o, &p) in out.iter_mut().zip(phi) {
            *o = power_law(p, beta);
        }
    }
}

register_model!(Family::Viscosity, "fry2024", EffectiveViscosity, Fry2024);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn beta_of_the_papers_cases() {
        // 0.565 + 0.85 (2.5 * 0.67 * sqrt(Re_p))^(2/3), computed by hand (25 digits)
        let f = |re_p| Fry2024 { re_p, ..Default::default() }.beta();
        assert_relative_eq!(f(1.0), 1.763_842_507_276_374, max_relative = 1e-14);
        assert_relative_eq!(f(10.0), 3.147_827_885_561_022, max_relative = 1e-14);
        assert_relative_eq!(f(0.1), 1.121_453_399_503_437, max_relative = 1e-14);
        // the paper's direct fit for (Re_p, theta) = (1, 0.67) is beta = 1.71
        assert_relative_eq!(f(1.0), 1.71, max_relative = 0.04);
        // a = 0: viscous limit beta0
        assert_eq!(Fry2024 { a: 0.0, ..Default::default() }.beta(), 0.565);
    }

    #[test]
    fn phase_stress_slope_is_beta_not_einstein() {
        // the phase stress eps nu_eff / nu_f is Fry's eta_eq / eta_f (eqs 32, 50, 52)
        let v = Fry2024::default();
        let beta = v.beta();
        let eta_eq = |phi: f64| (1.0 - phi) * v.ratio(phi);
        assert_eq!(v.ratio(0.0), 1.0);
        for h in [1e-4, 1e-6, 1e-8] {
            assert_relative_eq!((eta_eq(h) - 1.0) / h, beta, max_relative = 1e-3);
            assert_relative_eq!((v.ratio(h) - 1.0) / h, beta + 1.0, max_relative = 1e-3);
        }
        assert!((beta - 2.5).abs() > 0.5);
        assert_relative_eq!(eta_eq(0.3), 0.7f64.powf(-beta), max_relative = 1e-14);
        // the paper's direct fit of the reference case: eta_eq / eta_f = 0.5^-1.71 at phi = 0.5
        assert_relative_eq!(eta_eq(0.5), 0.5f64.powf(-1.71), max_relative = 0.04);
    }

    #[test]
    fn stress_ratio_of_the_column_alone_and_with_the_exchange() {
        // no exchange: the column's stress eps eta_f gamma gives the fluid fraction
        assert_relative_eq!(stress_ratio(0.7 * 1e-3 * 3.0, 0.0, 3.0, 1e-3, 1e-3), 0.7, max_relative = 1e-15);
        // the exchange's moment on top: beta gamma d^2 / 20 = 20 * 3 * 1e-6 / 20 = 3e-6 Pa
        // over eta_f gamma = 3e-3 Pa
        let (eta_f, d, gamma, beta) = (1e-3, 1e-3, 3.0, 20.0);
        assert_relative_eq!(stress_ratio(0.0, beta, gamma, d, eta_f), 1e-3, max_relative = 1e-14);
        // d^2 / 20 is the second moment of a sphere about its centre plane: the integral of
        // z^2 pi (R^2 - z^2) dz over the sphere's volume, by the midpoint rule
        let (radius, n) = (0.5 * d, 20_000);
        let h = 2.0 * radius / n as f64;
        let moment: f64 = (0..n)
            .map(|k| {
                let z = -radius + (k as f64 + 0.5) * h;
                z * z * std::f64::consts::PI * (radius * radius - z * z) * h
            })
            .sum::<f64>()
            / (4.0 / 3.0 * std::f64::consts::PI * radius.powi(3));
        let from_moment = beta * gamma * moment / (eta_f * gamma);
        assert_relative_eq!(stress_ratio(0.0, beta, gamma, d, eta_f), from_moment, max_relative = 1e-6);
        assert!(stress_ratio(0.0, beta, 0.0, d, eta_f).is_nan());
    }

    #[test]
    fn validate_refuses_out_of_range() {
        let d = Fry2024::default;
        let cases = [
            (Fry2024 { beta0: -0.1, ..d() }, "beta0"),
            (Fry2024 { a: 11.0, ..d() }, "a"),
            (Fry2024 { shields: 0.0, ..d() }, "shields"),
            (Fry2024 { re_p: 0.0, ..d() }, "re_p"),
            (Fry2024 { re_p: 2000.0, ..d() }, "re_p"),
            (Fry2024 { density_ratio: 1.0, ..d() }, "density_ratio"),
            (Fry2024 { density_ratio: f64::NAN, ..d() }, "density_ratio"),
        ];
        for (v, key) in cases {
            assert_eq!(v.validate().unwrap_err().key, key);
        }
        assert!(d().validate().is_ok());
    }

    #[test]
    fn parses_from_toml() {
        let v: Fry2024 = toml::from_str("shields = 0.3\nre_p = 10.0").unwrap();
        assert_eq!(v, Fry2024 { shields: 0.3, re_p: 10.0, ..Default::default() });
        assert!(toml::from_str::<Fry2024>("theta = 0.3").is_err());
    }

    proptest! {
        #[test]
        fn increasing(phi in 0f64..0.95, dphi in 1e-4f64..0.04, shields in 0.1f64..0.7, re_p in 0.1f64..10.0) {
            let v = Fry2024 { shields, re_p, ..Default::default() };
            prop_assert!(v.ratio(phi + dphi) > v.ratio(phi));
        }

        #[test]
        fn batch_equals_scalar(phi in proptest::collection::vec(0f64..0.99, 1..64), re_p in 0.1f64..10.0) {
            let v = Fry2024 { re_p, ..Default::default() };
            let mut out = vec![0.0; phi.len()];
            v.ratio_batch(&phi, &mut out);
            for (o, p) in out.iter().zip(&phi) {
                prop_assert_eq!(o.to_bits(), v.ratio(*p).to_bits());
            }
        }
    }
}
