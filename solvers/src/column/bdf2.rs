//! The variable-step second-order backward differentiation formula (BDF2) as a
//! backward-Euler row: with w = dt_n / dt_{n-1},
//!
//! (1 + 2w)/(1 + w) q^{n+1} - (1 + w) q^n + w^2/(1 + w) q^{n-1} = dt_n f(q^{n+1})
//!
//! (Hairer & Wanner, Solving ODEs II, section III.5, eq 5.9 for k = 2), which is the
//! backward-Euler row (q^{n+1} - q_old)/dt' = f with the mass term scaled by
//! s = (1 + 2w)/(1 + w) and q_old = a q^n - b q^{n-1}, a = (1 + w)/s, b = w^2/((1 + w) s).
//! The weights of the old values sum to one (a - b = 1), so a conserved sum of q is
//! conserved by the step. Coefficients that depend on q are second order when evaluated at
//! the linear extrapolation (1 + w) q^n - w q^{n-1} to the end of the step (the
//! semi-implicit BDF2 of Ascher, Ruuth & Wetton 1995, SIAM J. Numer. Anal. 32, 797), first
//! order when lagged at q^n.

/// The weights of one BDF2 step of ratio w.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bdf2 {
    ratio: f64,
    scale: f64,
    a: f64,
    b: f64,
}

impl Bdf2 {
    /// The weights for the step ratio `ratio` = dt_n / dt_{n-1} > 0.
    pub fn new(ratio: f64) -> Self {
        let w = ratio;
        let scale = (1.0 + 2.0 * w) / (1.0 + w);
        Self { ratio, scale, a: (1.0 + w) / scale, b: w * w / (1.0 + w) / scale }
    }

    /// The step ratio w.
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    /// The factor s = (1 + 2w)/(1 + w) of the mass term.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The old value of the backward-Euler row, a q^n - b q^{n-1}.
    #[inline]
    pub fn old(&self, now: f64, before: f64) -> f64 {
        self.a * now - self.b * before
    }

    /// The linear extrapolation of q to the end of the step, (1 + w) q^n - w q^{n-1}.
    #[inline]
    pub fn extrapolate(&self, now: f64, before: f64) -> f64 {
        (1.0 + self.ratio) * now - self.ratio * before
    }

    /// The mass factor and the old value of a row whose field must stay non-negative: the
    /// BDF2 ones where the old value a q^n - b q^{n-1} is non-negative, else backward
    /// Euler's (1, q^n), so that the M-matrix rows of a positive field keep it positive
    /// (a field falling by more than a/b = (1 + w)^2 / w^2 in one step, 4 at a constant
    /// step, is stepped at first order in that cell).
    #[inline]
    pub fn positive_row(&self, now: f64, before: f64) -> (f64, f64) {
        let old = self.old(now, before);
        if old >= 0.0 {
            (self.scale, old)
        } else {
            (1.0, now)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The formula is exact on quadratics in time for any step ratio: with q = t^2 and
    /// f = dq/dt = 2 t at t^{n+1}, the row holds to round-off.
    #[test]
    fn exact_on_quadratics_at_any_step_ratio() {
        for w in [0.3, 1.0, 1.7] {
            let (dt0, dt) = (0.1, 0.1 * w);
            let (t0, t1, t2) = (1.0, 1.0 + dt0, 1.0 + dt0 + dt);
            let q = |t: f64| t * t;
            let b = Bdf2::new(w);
            let lhs = b.scale() * (q(t2) - b.old(q(t1), q(t0))) / dt;
            assert!((lhs - 2.0 * t2).abs() < 1e-12, "w {w}: {lhs} vs {}", 2.0 * t2);
            assert!((b.extrapolate(t1, t0) - t2).abs() < 1e-14);
        }
    }

    /// The old values' weights sum to one, so sums are kept; a steep fall falls back to
    /// backward Euler.
    #[test]
    fn weights_sum_to_one_and_a_steep_fall_is_backward_euler() {
        let b = Bdf2::new(1.0);
        assert!((b.old(1.0, 1.0) - 1.0).abs() < 1e-15);
        assert_eq!(b.positive_row(1.0, 2.0), (b.scale(), b.old(1.0, 2.0)));
        assert_eq!(b.positive_row(1.0, 5.0), (1.0, 1.0));
    }
}
