//! Hindrance (crowding) correction of the drag force.

use crate::param::Describe;

/// The Reynolds number at which a hindrance evaluates the single-particle C_D and its own
/// Reynolds dependence, declared by the closure ([`Hindrance::reynolds_convention`]) so
/// that both solvers evaluate the drag the same way without probing the closure. Every
/// convention is Re* = c(phi) Re_p with Re_p = |u_f - v_p| d / nu_f the interstitial
/// particle Reynolds number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DragReynolds {
    /// Re* = Re_p (Richardson & Zaki 1954; Chassagne et al. 2023 eq 2.10; Maurin et al.
    /// 2015 eq 12)
    Interstitial,
    /// Re* = (1 - phi) Re_p, the Reynolds number of the superficial velocity (Di Felice
    /// 1994; Cheng et al. 2018, text after eq 7)
    Superficial,
}

impl DragReynolds {
    /// c(phi) = Re* / Re_p at volume fraction `phi` in [0, 1).
    #[inline]
    pub fn ratio(self, phi: f64) -> f64 {
        match self {
            DragReynolds::Interstitial => 1.0,
            DragReynolds::Superficial => 1.0 - phi,
        }
    }

    /// Re* from the interstitial `re_p` at volume fraction `phi`.
    #[inline]
    pub fn of(self, phi: f64, re_p: f64) -> f64 {
        self.ratio(phi) * re_p
    }
}

/// Factor multiplying the single-particle drag force at the same relative velocity, so
/// that the drag on a particle in a suspension of volume fraction `phi` is
/// F = f(phi, Re_p) (1/2) rho_f (pi d^2/4) C_D(Re*) |u_r| u_r, where
/// Re_p = |u_f - v_p| d / nu_f is the *interstitial* particle Reynolds number and
/// Re* that of the closure's declared convention ([`Hindrance::reynolds_convention`]).
#[typetag::serde(tag = "type")]
pub trait Hindrance: Describe + Send + Sync + std::fmt::Debug {
    /// Hindrance factor at volume fraction `phi` in [0, 1) and interstitial Re_p >= 0.
    fn factor(&self, phi: f64, re_p: f64) -> f64;
    /// The Reynolds number at which the single-particle C_D is evaluated.
    fn reynolds_convention(&self) -> DragReynolds;
    /// Whether [`Hindrance::factor`] depends on Re_p (a solver may then tabulate it per
    /// cell instead of evaluating it per particle).
    fn depends_on_reynolds(&self) -> bool;
    /// Re* of the declared convention at `phi` and interstitial `re_p`.
    fn drag_reynolds(&self, phi: f64, re_p: f64) -> f64 {
        self.reynolds_convention().of(phi, re_p)
    }
    /// Factor over slices of equal length.
    fn factor_batch(&self, phi: &[f64], re_p: &[f64], out: &mut [f64]) {
        for ((o, &p), &r) in out.iter_mut().zip(phi).zip(re_p) {
            *o = self.factor(p, r);
        }
    }
}
