//! An out-of-tree closure crate for saltus: the Cheng (2009) drag law of a sphere.
//!
//! A model is a `Serialize + Deserialize` struct that derives [`Describe`], implements a
//! family trait (here [`DragLaw`]) under a typetag name, and is registered with
//! [`register_model!`]. The binary `saltus-custom` calls [`link`] and then the saltus
//! command line, so that `saltus-custom models drag` lists `cheng2009` and a scene can say
//! `[closures.drag] type = "cheng2009"`.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragLaw, Limit};
use serde::{Deserialize, Serialize};

/// Cheng (2009) drag coefficient of a smooth sphere
///
/// C_D = 24/Re_p (1 + a Re_p)^b + c (1 - exp(-k Re_p^m))
///
/// * Source: Cheng, N.-S. 2009, "Comparison of formulas for drag coefficient and settling
///   velocity of spherical particles", Powder Technol. 189(3), 395-398, eq 1
///   (doi:10.1016/j.powtec.2008.07.006). Not Cheng 1997 (J. Hydraul. Eng. 123(2),
///   149-152), which gives a settling-velocity formula, not this C_D.
/// * Defaults: the paper's fit, `a = 0.27`, `b = 0.43`, `c = 0.47`, `k = 0.04`, `m = 0.38`.
/// * Valid range: subcritical flow, 0 < Re_p <= 2e5 (the fit data; no drag crisis);
///   `b` in [0, 0.8], `k` in [0.01, 1] and `m` in [0.2, 1]: beyond them C_D reaches its
///   Newton value `c` only far above Re_p = 1e12 (`saltus closure check` found both: with
///   b = 0.99 or m = 4e-9 the declared limit C_D -> c does not show).
///   Tends to Stokes' 24/Re_p as Re_p -> 0 and to `c` as Re_p -> inf (C_D Re_p -> 24,
///   C_D^inf = 0.47); C_D(0.1) = 242.77, C_D(1000) = 0.47.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "cheng2009",
    source = "Cheng 2009, Powder Technol. 189, 395-398, eq 1",
    equation = "C_D = 24/Re_p (1 + a Re_p)^b + c (1 - exp(-k Re_p^m))",
    limits = [Limit::Stokes { cd_re: 24.0 }, Limit::HighReynolds]
)]
pub struct Cheng2009 {
    /// coefficient a of the viscous correction (1 + a Re_p)^b
    #[param(range = "[0, 10]", unit = "-")]
    pub a: f64,
    /// exponent b of the viscous correction
    #[param(range = "[0, 0.8]", unit = "-")]
    pub b: f64,
    /// drag coefficient at large Re_p (Newton regime)
    #[param(range = "[0, 2]", unit = "-")]
    pub c: f64,
    /// rate k of the approach to the Newton regime
    #[param(range = "[0.01, 1]", unit = "-")]
    pub k: f64,
    /// power m of Re_p in the approach to the Newton regime
    #[param(range = "[0.2, 1]", unit = "-")]
    pub m: f64,
}

impl Default for Cheng2009 {
    fn default() -> Self {
        Self { a: 0.27, b: 0.43, c: 0.47, k: 0.04, m: 0.38 }
    }
}

#[typetag::serde(name = "cheng2009")]
impl DragLaw for Cheng2009 {
    fn cd(&self, re_p: f64) -> f64 {
        self.cd_re(re_p) / re_p
    }

    // written as C_D Re_p so that Re_p = 0 (a particle at rest in the fluid) gives 24, not
    // 0 * inf
    fn cd_re(&self, re_p: f64) -> f64 {
        24.0 * (1.0 + self.a * re_p).powf(self.b) + self.c * re_p * (-(-self.k * re_p.powf(self.m)).exp_m1())
    }

    fn cd_inf(&self) -> f64 {
        self.c
    }
}

register_model!(Family::Drag, "cheng2009", DragLaw, Cheng2009);

/// Keep this crate's registrations in a binary: call it once before the saltus command
/// line. Returns the number of registered models.
pub fn link() -> usize {
    saltus_core::registry::models().len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn values_of_the_paper_formula() {
        let m = Cheng2009::default();
        // the formula evaluated directly, as printed
        let printed = |re: f64| 24.0 / re * (1.0 + 0.27 * re).powf(0.43) + 0.47 * (1.0 - (-0.04 * re.powf(0.38)).exp());
        for re in [1e-3, 0.1, 1.0, 10.0, 1e3, 5e4, 2e5] {
            assert_relative_eq!(m.cd(re), printed(re), max_relative = 1e-12);
        }
        assert_relative_eq!(m.cd(0.1), 242.77, max_relative = 2e-5);
        assert_relative_eq!(m.cd(1000.0), 0.47, max_relative = 1e-2);
    }

    #[test]
    fn limits() {
        let m = Cheng2009::default();
        assert_eq!(m.cd_re(0.0), 24.0);
        assert_relative_eq!(m.cd_re(1e-9), 24.0, max_relative = 1e-8);
        assert_relative_eq!(m.cd(1e12), 0.47, max_relative = 1e-2);
    }
}
