//! Single-particle drag coefficient.

use crate::param::Describe;

/// Drag coefficient of an isolated particle, C_D(Re_p), with
/// Re_p = |u_f - v_p| d / nu_f (or the convention the hindrance model asks for, see
/// [`crate::Hindrance::drag_reynolds`]). The drag force is
/// F = (1/2) rho_f (pi d^2/4) C_D |u_r| u_r.
#[typetag::serde(tag = "type")]
pub trait DragLaw: Describe + Send + Sync + std::fmt::Debug {
    /// C_D at particle Reynolds number `re_p` (> 0).
    fn cd(&self, re_p: f64) -> f64;

    /// C_D * Re_p, finite as Re_p -> 0 (24 in the Stokes limit); solvers use it so that a
    /// particle at rest relative to the fluid is not a 0 * inf.
    fn cd_re(&self, re_p: f64) -> f64 {
        self.cd(re_p) * re_p
    }

    /// High-Reynolds-number limit C_D^inf (0 for Stokes drag), used by the quadratic drag
    /// dissipation of Chassagne 2023 eq 3.13.
    fn cd_inf(&self) -> f64;

    /// C_D Re_p over a slice (see [`DragLaw::cd_re`]); `out.len()` must equal
    /// `re_p.len()`. The Eulerian solver's drag kernel calls it once per column.
    fn cd_re_batch(&self, re_p: &[f64], out: &mut [f64]) {
        for (o, &r) in out.iter_mut().zip(re_p) {
            *o = self.cd_re(r);
        }
    }
    /// C_D over a slice; `out.len()` must equal `re_p.len()`.
    fn cd_batch(&self, re_p: &[f64], out: &mut [f64]) {
        for (o, &r) in out.iter_mut().zip(re_p) {
            *o = self.cd(r);
        }
    }
}
