//! Effective viscosity of the fluid phase.

use crate::param::Describe;

/// Effective fluid viscosity as a multiple of the clear-fluid viscosity:
/// nu_eff = nu_f * ratio(phi).
#[typetag::serde(tag = "type")]
pub trait EffectiveViscosity: Describe + Send + Sync + std::fmt::Debug {
    /// nu_eff / nu_f at volume fraction `phi`.
    fn ratio(&self, phi: f64) -> f64;

    /// Largest volume fraction at which the law is finite (1 for laws without divergence).
    fn phi_limit(&self) -> f64 {
        1.0
    }

    /// Ratio over a slice.
    fn ratio_batch(&self, phi: &[f64], out: &mut [f64]) {
        for (o, &p) in out.iter_mut().zip(phi) {
            *o = self.ratio(p);
        }
    }
}
