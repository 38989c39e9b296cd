//! The 3/2-law fit of a transport-rate sweep: qs* = a (theta - theta_c)^{3/2} (Wilson
//! 1987, the form of Maurin et al. 2015 figure 6) by weighted least squares in (a,
//! theta_c), with their standard errors.
//!
//! For a given theta_c the model is linear in a, so the fit scans theta_c below the
//! smallest fitted theta with a at its linear least-squares value, then refines the best
//! pair on both with the law's own Jacobian by [`crate::least_squares`]
//! (Levenberg-Marquardt). The covariance is (J^T W J)^-1 scaled by the reduced
//! chi^2 (the residual scatter, as scipy's `curve_fit` does by default), so that points
//! without errors of their own (an Eulerian sweep, weights 1) get errors from their
//! scatter about the law.
//!
//! A series where only some points carry an error (a DEM run too short for its blocking
//! test to give one) weighs each point without one as the least certain of the others:
//! its error is taken as its qs* times the largest relative error of the points that have
//! one. Weighing it 1 beside weights of 1/se^2 (1e4-1e6 for DEM rates) would drop it from
//! the fit without a word; counting it as certain would let it pull the law alone.

use crate::least_squares::LeastSquares;

/// A fitted 3/2 law.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Fit {
    /// coefficient a
    pub a: f64,
    /// standard error of a
    pub a_stderr: f64,
    /// threshold theta_c
    pub theta_c: f64,
    /// standard error of theta_c
    pub theta_c_stderr: f64,
    /// points fitted
    pub n: usize,
    /// root-mean-square residual (in qs*)
    pub rms: f64,
    /// theta_c ended at the smallest fitted theta: the points rise faster than a 3/2
    /// power of any threshold below them, and the errors do not bound theta_c
    pub at_bound: bool,
    /// points without an error of their own in a series where others have one, weighed
    /// with the largest relative error of those (module comment)
    pub n_stand_in: usize,
}

fn law(a: f64, c: f64, x: f64) -> f64 {
    let s = (x - c).max(0.0);
    a * s * s.sqrt()
}

/// d law / d(a, c).
fn law_derivative(a: f64, c: f64, x: f64) -> [f64; 2] {
    let s = (x - c).max(0.0);
    [s * s.sqrt(), -1.5 * a * s.sqrt()]
}

/// Fit y = a (x - c)^{3/2} to the points `(x, y, sigma)`, weighted by 1/sigma^2. A point
/// with `None` (or a non-finite or non-positive sigma) takes the largest relative error of
/// the points that have one (module comment); when none has one, every point weighs 1.
/// The error says why not: fewer than three points, a theta that is not positive, points
/// that do not determine the law, no convergence.
pub fn fit(points: &[(f64, f64, Option<f64>)]) -> Result<Fit, String> {
    let own = |s: Option<f64>| s.filter(|s| *s > 0.0 && s.is_finite());
    let finite: Vec<(f64, f64, Option<f64>)> = points
        .iter()
        .copied()
        .filter(|(x, y, _)| x.is_finite() && y.is_finite())
        .map(|(x, y, s)| (x, y, own(s)))
        .collect();
    // the largest relative error of the points that have one, for those that have none
    let worst = finite
        .iter()
        .filter_map(|&(_, y, s)| s.map(|s| s / y.abs()))
        .filter(|r| r.is_finite())
        .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
    let mut n_stand_in = 0;
    let pts: Vec<(f64, f64, f64)> = finite
        .iter()
        .map(|&(x, y, s)| {
            let s = s.or_else(|| {
                let stood = worst.map(|r| r * y.abs()).filter(|s| *s > 0.0 && s.is_finite());
                n_stand_in += usize::from(stood.is_some());
                stood
            });
            (x, y, s.map_or(1.0, |s| 1.0 / (s * s)))
        })
        .collect();
    let n = pts.len();
    if n < 3 {
        return Err(format!("{n} points with finite values, fewer than the 3 a 3/2 law takes"));
    }
    let xmin = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    if xmin.is_nan() || xmin <= 0.0 {
        return Err(format!("a point at theta = {xmin}: the law's threshold lies in 0 < theta_c < theta"));
    }
    let chi2 = |a: f64, c: f64| pts.iter().map(|&(x, y, w)| w * (y - law(a, c, x)).powi(2)).sum::<f64>();
    let best_a = |c: f64| {
        let (mut num, mut den) = (0.0, 0.0);
        for &(x, y, w) in &pts {
            let b = law(1.0, c, x);
            num += w * b * y;
            den += w * b * b;
        }
        num / den
    };
    // scan theta_c over [0, xmin)
    let steps = 4000;
    let (mut c, mut a) = (0.0, best_a(0.0));
    let mut best = chi2(a, c);
    for k in 1..steps {
        let ck = xmin * k as f64 / steps as f64;
        let ak = best_a(ck);
        let r = chi2(ak, ck);
        if r < best {
            (a, c, best) = (ak, ck, r);
        }
    }
    if !(a.is_finite() && best.is_finite()) {
        return Err("the points do not determine the law: no finite chi^2 at any threshold".into());
    }
    // the scan's best pair refined on both by the one least-squares solver, inside
    // theta_c < xmin where every point lies above the threshold
    let x: Vec<f64> = pts.iter().map(|p| p.0).collect();
    let y: Vec<f64> = pts.iter().map(|p| p.1).collect();
    let w: Vec<f64> = pts.iter().map(|p| p.2).collect();
    let start = [a, c];
    let solution = LeastSquares::new(&["a", "theta_c"], &start, n)
        .weights(&w)
        .min_points(3)
        .max_correlation(None)
        // to round-off: the scan's pair is already close, and a and theta_c are reported to
        // their last digits
        .tolerances(1e-14, 0.0)
        .jacobian(|p| Some(x.iter().flat_map(|&x| law_derivative(p[0], p[1], x)).collect()))
        .solve(|p| (p[1] < xmin).then(|| x.iter().zip(&y).map(|(&x, y)| law(p[0], p[1], x) - y).collect()))?;
    let (a, c) = (solution.params[0], solution.params[1]);
    let at_bound = c > xmin * (1.0 - 1e-3);
    Ok(Fit {
        a,
        a_stderr: solution.stderr_independent[0],
        theta_c: c,
        theta_c_stderr: solution.stderr_independent[1],
        n,
        rms: solution.rms,
        at_bound,
        n_stand_in,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points on an exact 3/2 law give the law back, with errors that vanish with the
    /// residuals.
    #[test]
    fn an_exact_law_is_recovered() {
        let pts: Vec<_> = [0.08, 0.1, 0.15, 0.2, 0.3, 0.5].iter().map(|&x| (x, law(11.8, 0.047, x), None)).collect();
        let f = fit(&pts).unwrap();
        assert!((f.a - 11.8).abs() < 1e-8 * 11.8, "{f:?}");
        assert!((f.theta_c - 0.047).abs() < 1e-9, "{f:?}");
        assert!(f.a_stderr < 1e-6 && f.theta_c_stderr < 1e-8, "{f:?}");
    }

    /// With scatter, the true law lies within a few standard errors of the fit, and
    /// errors of the points of 1 % give an error of a of the order of 1 %.
    #[test]
    fn scattered_points_give_errors_that_cover_the_law() {
        // alternating +-1 % relative deviations
        let pts: Vec<_> = (0..12)
            .map(|k| {
                let x = 0.1 + 0.05 * k as f64;
                let y = law(8.0, 0.047, x) * if k % 2 == 0 { 1.01 } else { 0.99 };
                (x, y, Some(0.01 * y))
            })
            .collect();
        let f = fit(&pts).unwrap();
        assert!((f.a - 8.0).abs() < 3.0 * f.a_stderr, "{f:?}");
        assert!((f.theta_c - 0.047).abs() < 3.0 * f.theta_c_stderr, "{f:?}");
        assert!(f.a_stderr > 1e-3 * 8.0 && f.a_stderr < 0.05 * 8.0, "{f:?}");
    }

    /// A point without an error beside points with one weighs as the least certain of
    /// them: the fit is the one where its error is its qs* times their largest relative
    /// error, and it moves the law (it is not dropped as a weight of 1 among 1/se^2 would).
    #[test]
    fn a_point_without_an_error_weighs_as_the_least_certain_point_with_one() {
        let xs = [0.08, 0.1, 0.15, 0.2, 0.3];
        let rel = [0.06, 0.05, 0.03, 0.02, 0.01];
        // the last point off the law by 20 %, so that dropping it or not shows
        let y = |k: usize| law(10.0, 0.05, xs[k]) * if k == 4 { 1.2 } else { 1.0 + 0.01 * (k as f64 - 2.0) };
        let with: Vec<_> = (0..5).map(|k| (xs[k], y(k), Some(rel[k] * y(k)))).collect();
        let mut without = with.clone();
        without[4].2 = None;
        let stood = {
            let mut p = with.clone();
            p[4].2 = Some(0.06 * y(4));
            fit(&p).unwrap()
        };
        let dropped = fit(&with[..4]).unwrap();
        let f = fit(&without).unwrap();
        assert_eq!(f.n_stand_in, 1);
        assert_eq!(stood.n_stand_in, 0);
        assert!((f.a - stood.a).abs() < 1e-9 * stood.a && (f.theta_c - stood.theta_c).abs() < 1e-12, "{f:?} {stood:?}");
        assert!((f.a - dropped.a).abs() > 0.01 * dropped.a, "{f:?} {dropped:?}");
    }

    /// With no point carrying an error, every point weighs 1 and none is stood in.
    #[test]
    fn points_without_errors_weigh_alike() {
        let pts: Vec<_> = [0.08, 0.1, 0.15, 0.2].iter().map(|&x| (x, law(9.0, 0.04, x) * 1.01, None)).collect();
        assert_eq!(fit(&pts).unwrap().n_stand_in, 0);
    }

    #[test]
    fn too_few_points_are_not_fitted() {
        assert!(fit(&[(0.1, 0.1, None), (0.2, 0.5, None)]).is_err());
    }
}
