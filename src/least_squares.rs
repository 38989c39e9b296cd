//! Weighted nonlinear least squares by Levenberg-Marquardt (Levenberg 1944, Marquardt
//! 1963; Press et al., Numerical Recipes, 3rd ed., section 15.5.2), with the parameters'
//! covariance from the Jacobian: the one solver of the fits of the command-line layer
//! (the sweep's 3/2 law, the closures of `diagnose --fit`, the slopes of the diagnoses).
//!
//! The model is a residual function r(p) (one entry per point, model minus data) that may
//! refuse a parameter vector (`None`: outside the model's valid range); a refused step is
//! treated as one that does not lower chi^2 = sum w r^2, so the fit stays inside the range.
//! The Jacobian is the model's own when it has one ([`LeastSquares::jacobian`]), else
//! forward differences. The covariance is s^2 (J^T W J)^-1 with s^2 = chi^2 / (n - m), the
//! residual scatter, as scipy's `curve_fit` scales it by default: points with weights 1
//! get errors from their scatter, and weights 1/sigma^2 give errors that also follow the
//! scatter about the model rather than the sigmas alone.

/// A converged fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// fitted parameters
    pub params: Vec<f64>,
    /// standard errors with the points taken as independent: sqrt(s^2 (J^T W J)^-1)_ii,
    /// s^2 = chi^2 / (n - m) (NaN when n = m)
    pub stderr_independent: Vec<f64>,
    /// the same inflated by sqrt((1 + r1) / (1 - r1)), r1 the lag-1 autocorrelation of the
    /// weighted residuals in the order of the points (when positive): the variance of a
    /// mean of AR(1)-correlated values, so that neighbouring cells sharing grains count
    /// less than independent ones
    pub stderr: Vec<f64>,
    /// covariance of the parameters (row-major m x m), with the inflation of `stderr`
    pub covariance: Vec<f64>,
    /// lag-1 autocorrelation of the weighted residuals
    pub r1: f64,
    /// RMS of the residuals, unweighted
    pub rms: f64,
    /// chi^2 = sum w r^2 at the fitted parameters
    pub chi2: f64,
    /// number of points
    pub points: usize,
}

/// Fewest points a fit of `m` parameters takes by default: the parameters and three
/// degrees of freedom for the residual variance.
pub fn min_points(m: usize) -> usize {
    m + 3
}

/// Largest |correlation| between two fitted parameters (from (J^T W J)^-1) before a fit
/// is called singular by default: beyond it the points determine only a combination of
/// the two.
pub const MAX_CORRELATION: f64 = 0.999;

/// Iterations before a fit is reported as not converged.
const MAX_ITERATIONS: usize = 500;

/// Marquardt's damping lambda at the start of a nonlinear fit.
const DAMPING: f64 = 1e-3;

/// Row-major n x m derivative of the residuals in the parameters at `p`.
type Jacobian<'a> = Box<dyn FnMut(&[f64]) -> Option<Vec<f64>> + 'a>;

/// A weighted least-squares fit of `p0.len()` parameters to `n` points, set up by its
/// methods and run by [`LeastSquares::solve`]; [`fit`] is the unweighted default.
pub struct LeastSquares<'a> {
    names: &'a [&'a str],
    p0: &'a [f64],
    n: usize,
    weights: Option<&'a [f64]>,
    jacobian: Option<Jacobian<'a>>,
    min_points: usize,
    max_correlation: Option<f64>,
    linear: bool,
    step_tolerance: f64,
    gain_tolerance: f64,
}

impl<'a> LeastSquares<'a> {
    /// A fit of the parameters `names` from `p0` to `n` points, weights 1, forward
    /// differences, at least [`min_points`] points and a refusal beyond
    /// [`MAX_CORRELATION`].
    pub fn new(names: &'a [&'a str], p0: &'a [f64], n: usize) -> Self {
        LeastSquares {
            names,
            p0,
            n,
            weights: None,
            jacobian: None,
            min_points: min_points(p0.len()),
            max_correlation: Some(MAX_CORRELATION),
            linear: false,
            step_tolerance: 1e-10,
            gain_tolerance: 1e-14,
        }
    }

    /// Weights w of the points, 1/sigma^2 for points of standard error sigma (finite and
    /// non-negative, one per point).
    pub fn weights(mut self, w: &'a [f64]) -> Self {
        self.weights = Some(w);
        self
    }

    /// The model's own derivative of the (unweighted) residuals, row-major n x m, `None`
    /// where it is not defined.
    pub fn jacobian(mut self, j: impl FnMut(&[f64]) -> Option<Vec<f64>> + 'a) -> Self {
        self.jacobian = Some(Box::new(j));
        self
    }

    /// Fewest points the fit takes (at least the number of parameters).
    pub fn min_points(mut self, n: usize) -> Self {
        self.min_points = n;
        self
    }

    /// The largest |correlation| between two parameters before the fit is refused as
    /// singular; `None`: any, the standard errors then saying how little is determined.
    pub fn max_correlation(mut self, c: Option<f64>) -> Self {
        self.max_correlation = c;
        self
    }

    /// The residuals are linear in the parameters: the undamped Gauss-Newton step from
    /// `p0` is the minimum, and the fit stops after it rather than iterating on round-off.
    pub fn linear(mut self) -> Self {
        self.linear = true;
        self
    }

    /// When the fit has converged: a step below `step` of each parameter's magnitude, or a
    /// decrease of chi^2 below `gain` of it (defaults 1e-10 and 1e-14). A gain of 0 runs
    /// the fit to round-off: to where chi^2 no longer decreases, then by Gauss-Newton steps
    /// while they shrink, to where the gradient of chi^2 is round-off.
    pub fn tolerances(mut self, step: f64, gain: f64) -> Self {
        (self.step_tolerance, self.gain_tolerance) = (step, gain);
        self
    }

    /// Fit the residuals `residuals(p)` (model minus data, unweighted); the error says
    /// why the points cannot support the fit (too few points, a singular or degenerate
    /// regression, no convergence), naming the parameters by their names.
    pub fn solve(self, mut residuals: impl FnMut(&[f64]) -> Option<Vec<f64>>) -> Result<Solution, String> {
        let LeastSquares {
            names,
            p0,
            n,
            weights,
            mut jacobian,
            min_points,
            max_correlation,
            linear,
            step_tolerance,
            gain_tolerance,
        } = self;
        let m = p0.len();
        let fewest = min_points.max(m).max(1);
        if n < fewest {
            return Err(format!("too few cells: {n} for {m} parameters (at least {fewest} needed)"));
        }
        // residuals and Jacobian rows scaled by sqrt(w): chi^2 is then their sum of squares
        let root_w: Option<Vec<f64>> = match weights {
            None => None,
            Some(w) if w.len() != n => return Err(format!("{} weights for {n} points", w.len())),
            Some(w) => match w.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
                Some(k) => return Err(format!("the weight of point {k} is {}, not a finite number >= 0", w[k])),
                None => Some(w.iter().map(|w| w.sqrt()).collect()),
            },
        };
        let scale_rows = |mut v: Vec<f64>, width: usize| {
            if let Some(rw) = &root_w {
                for (row, s) in v.chunks_mut(width).zip(rw) {
                    row.iter_mut().for_each(|x| *x *= s);
                }
            }
            v
        };
        let ssr = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
        let mut p = p0.to_vec();
        let first =
            residuals(&p).ok_or_else(|| "the starting parameters are outside the closure's range".to_string())?;
        if first.len() != n || !first.iter().all(|v| v.is_finite()) {
            return Err("the closure gives no finite value in some cell at the starting parameters".into());
        }
        let (mut r, mut raw) = (scale_rows(first.clone(), 1), first);
        let mut weighted = |p: &[f64]| -> Option<(Vec<f64>, Vec<f64>)> {
            let r = residuals(p).filter(|r| r.len() == n && r.iter().all(|v| v.is_finite()))?;
            Some((scale_rows(r.clone(), 1), r))
        };
        let mut derivative =
            |p: &[f64], r: &[f64], weighted: &mut dyn FnMut(&[f64]) -> Option<Vec<f64>>| match &mut jacobian {
                Some(j) => {
                    j(p).filter(|j| j.len() == n * m && j.iter().all(|v| v.is_finite())).map(|j| scale_rows(j, m))
                }
                None => forward_differences(p, r, weighted),
            };
        let mut s = ssr(&r);
        let mut lambda = if linear { 0.0 } else { DAMPING };
        let mut converged = false;
        for _ in 0..MAX_ITERATIONS {
            let j = derivative(&p, &r, &mut |q| weighted(q).map(|v| v.0))
                .ok_or("the closure's derivative is not defined at the parameters")?;
            let (a, g) = normal_equations(&j, &r, m);
            let mut stepped = false;
            while lambda < 1e12 {
                let mut damped = a.clone();
                for i in 0..m {
                    damped[i * m + i] += lambda * a[i * m + i].max(1e-300);
                }
                let Some(dp) = solve(&damped, &g, m) else {
                    lambda = (lambda * 10.0).max(1e-12);
                    continue;
                };
                let trial: Vec<f64> = p.iter().zip(&dp).map(|(x, d)| x - d).collect();
                match weighted(&trial) {
                    Some((rt, raw_t)) if ssr(&rt) <= s => {
                        let s_new = ssr(&rt);
                        let small_step =
                            dp.iter().zip(&trial).all(|(d, x)| d.abs() <= step_tolerance * (x.abs() + 1e-10));
                        let small_gain = s - s_new <= gain_tolerance * s.max(1e-300);
                        p = trial;
                        (r, raw) = (rt, raw_t);
                        s = s_new;
                        lambda = (lambda / 10.0).max(1e-12);
                        stepped = true;
                        converged = linear || small_step || small_gain;
                        break;
                    }
                    _ => lambda = (lambda * 10.0).max(1e-12),
                }
            }
            if !stepped {
                // no step lowers chi^2: a minimum (within round-off)
                converged = true;
            }
            if converged {
                break;
            }
        }
        if !converged {
            return Err(format!("no convergence in {MAX_ITERATIONS} iterations"));
        }
        if gain_tolerance <= 0.0 {
            // near the minimum chi^2 is flat to round-off, so that a step's gain no longer
            // says where the minimum is, while the gradient J^T W r it is found from stays
            // accurate: undamped Gauss-Newton steps, taken while they keep shrinking (the
            // contraction of Newton's iteration), reach it to round-off
            let mut last = f64::INFINITY;
            for _ in 0..MAX_ITERATIONS {
                let Some(j) = derivative(&p, &r, &mut |q| weighted(q).map(|v| v.0)) else { break };
                let (a, g) = normal_equations(&j, &r, m);
                let Some(dp) = solve(&a, &g, m) else { break };
                let size = dp.iter().zip(&p).map(|(d, x)| d.abs() / (x.abs() + 1e-10)).fold(0.0, f64::max);
                if size.is_nan() || size >= last {
                    break;
                }
                let trial: Vec<f64> = p.iter().zip(&dp).map(|(x, d)| x - d).collect();
                match weighted(&trial) {
                    Some((rt, raw_t)) if ssr(&rt) <= s * (1.0 + 1e-12) => {
                        s = ssr(&rt);
                        (p, r, raw, last) = (trial, rt, raw_t, size);
                    }
                    _ => break,
                }
            }
        }
        let j = derivative(&p, &r, &mut |q| weighted(q).map(|v| v.0))
            .ok_or("the closure's derivative is not defined at the fitted parameters")?;
        let (a, _) = normal_equations(&j, &r, m);
        let diag: Vec<f64> = (0..m).map(|i| a[i * m + i]).collect();
        if let Some(i) = diag.iter().position(|d| d.is_nan() || *d <= 0.0) {
            return Err(format!("singular regression: the cells do not depend on `{}`", names[i]));
        }
        // the correlation form of J^T W J: unit diagonal, so its conditioning is the
        // parameters'
        let scaled: Vec<f64> = (0..m * m).map(|k| a[k] / (diag[k / m] * diag[k % m]).sqrt()).collect();
        let inv = invert(&scaled, m).ok_or("singular regression: the parameters are not separately determined")?;
        if let Some(limit) = max_correlation {
            for i in 0..m {
                for k in (i + 1)..m {
                    let c = inv[i * m + k] / (inv[i * m + i] * inv[k * m + k]).sqrt();
                    if c.is_nan() || c.abs() >= limit {
                        return Err(format!(
                            "singular regression: `{}` and `{}` are not separately determined by these cells (correlation {c:.4})",
                            names[i], names[k]
                        ));
                    }
                }
            }
        }
        let s2 = if n > m { s / (n - m) as f64 } else { f64::NAN };
        let stderr_independent: Vec<f64> = (0..m).map(|i| (s2 * inv[i * m + i] / diag[i]).sqrt()).collect();
        let r1 = lag1(&r);
        let inflation = if r1 > 0.0 { ((1.0 + r1) / (1.0 - r1).max(1e-12)).sqrt() } else { 1.0 };
        let stderr: Vec<f64> = stderr_independent.iter().map(|e| e * inflation).collect();
        let covariance: Vec<f64> =
            (0..m * m).map(|k| s2 * inflation * inflation * inv[k] / (diag[k / m] * diag[k % m]).sqrt()).collect();
        let rms = (ssr(&raw) / n as f64).sqrt();
        Ok(Solution { params: p, stderr_independent, stderr, covariance, r1, rms, chi2: s, points: n })
    }
}

/// Fit `p0.len()` parameters from `p0` to the unweighted residuals `residuals(p)` of `n`
/// points with the defaults of [`LeastSquares::new`].
pub fn fit(
    names: &[&str],
    p0: &[f64],
    n: usize,
    residuals: impl FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Result<Solution, String> {
    LeastSquares::new(names, p0, n).solve(residuals)
}

/// Forward-difference Jacobian (backward where the forward point is refused), row-major
/// n x m.
fn forward_differences(
    p: &[f64],
    r: &[f64],
    residuals: &mut dyn FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Option<Vec<f64>> {
    let (n, m) = (r.len(), p.len());
    let mut j = vec![0.0; n * m];
    for k in 0..m {
        let h = 1e-6 * p[k].abs().max(1e-3);
        let mut q = p.to_vec();
        q[k] = p[k] + h;
        let (rq, step) = match residuals(&q) {
            Some(v) => (v, h),
            None => {
                q[k] = p[k] - h;
                (residuals(&q)?, -h)
            }
        };
        for i in 0..n {
            j[i * m + k] = (rq[i] - r[i]) / step;
        }
    }
    Some(j)
}

/// J^T J and J^T r.
fn normal_equations(j: &[f64], r: &[f64], m: usize) -> (Vec<f64>, Vec<f64>) {
    let mut a = vec![0.0; m * m];
    let mut g = vec![0.0; m];
    for (row, ri) in j.chunks(m).zip(r) {
        for i in 0..m {
            g[i] += row[i] * ri;
            for k in 0..m {
                a[i * m + k] += row[i] * row[k];
            }
        }
    }
    (a, g)
}

/// Solve a x = b by Gaussian elimination with partial pivoting; None when a pivot falls
/// below 1e-13 of the largest.
fn solve(a: &[f64], b: &[f64], m: usize) -> Option<Vec<f64>> {
    let mut aug: Vec<Vec<f64>> =
        (0..m).map(|i| a[i * m..(i + 1) * m].iter().copied().chain([b[i]]).collect()).collect();
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..m {
        let piv = (c..m).max_by(|&x, &y| aug[x][c].abs().total_cmp(&aug[y][c].abs()))?;
        let pivot = aug[piv][c].abs();
        if pivot.is_nan() || pivot <= 1e-13 * scale {
            return None;
        }
        aug.swap(c, piv);
        for rr in (c + 1)..m {
            let f = aug[rr][c] / aug[c][c];
            let (top, bottom) = aug.split_at_mut(rr);
            for (x, y) in bottom[0][c..].iter_mut().zip(&top[c][c..]) {
                *x -= f * y;
            }
        }
    }
    let mut x = vec![0.0; m];
    for c in (0..m).rev() {
        let s: f64 = ((c + 1)..m).map(|k| aug[c][k] * x[k]).sum();
        x[c] = (aug[c][m] - s) / aug[c][c];
    }
    Some(x)
}

/// Inverse of a, column by column; None when singular.
fn invert(a: &[f64], m: usize) -> Option<Vec<f64>> {
    let mut inv = vec![0.0; m * m];
    for c in 0..m {
        let e: Vec<f64> = (0..m).map(|i| if i == c { 1.0 } else { 0.0 }).collect();
        let x = solve(a, &e, m)?;
        for i in 0..m {
            inv[i * m + c] = x[i];
        }
    }
    Some(inv)
}

/// Lag-1 autocorrelation of `r` about its mean (0 below three values).
fn lag1(r: &[f64]) -> f64 {
    if r.len() < 3 {
        return 0.0;
    }
    let mean = r.iter().sum::<f64>() / r.len() as f64;
    let var: f64 = r.iter().map(|v| (v - mean).powi(2)).sum();
    if var <= 0.0 {
        return 0.0;
    }
    r.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum::<f64>() / var
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight line y = 2 + 3 x through five points with alternating residuals +-e:
    /// the fit returns the line, and the standard errors of ordinary least squares,
    /// s^2 = SSR / (n - 2) times the diagonal of (X^T X)^-1.
    #[test]
    fn a_line_and_its_textbook_standard_errors() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let e = [0.1, -0.1, 0.1, -0.1, 0.0];
        let y: Vec<f64> = x.iter().zip(&e).map(|(x, e)| 2.0 + 3.0 * x + e).collect();
        let s =
            fit(&["a", "b"], &[0.0, 0.0], 5, |p| Some(x.iter().zip(&y).map(|(x, y)| p[0] + p[1] * x - y).collect()))
                .unwrap();
        // closed form: b = Sxy / Sxx, a = ybar - b xbar (xbar = 2, Sxx = 10)
        let ybar = y.iter().sum::<f64>() / 5.0;
        let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - 2.0) * (y - ybar)).sum();
        let (b, a) = (sxy / 10.0, ybar - 2.0 * sxy / 10.0);
        assert!((s.params[0] - a).abs() < 1e-9 && (s.params[1] - b).abs() < 1e-9, "{:?}", s.params);
        let ssr: f64 = x.iter().zip(&y).map(|(x, y)| (a + b * x - y).powi(2)).sum();
        let s2 = ssr / 3.0;
        let se_b = (s2 / 10.0).sqrt();
        let se_a = (s2 * (1.0 / 5.0 + 4.0 / 10.0)).sqrt();
        assert!((s.stderr_independent[1] - se_b).abs() < 1e-6 * se_b, "{} {se_b}", s.stderr_independent[1]);
        assert!((s.stderr_independent[0] - se_a).abs() < 1e-6 * se_a);
        // alternating residuals are anti-correlated: no inflation
        assert!(s.r1 < 0.0 && s.stderr == s.stderr_independent);
    }

    /// A weighted straight line y = a + b x with its Jacobian, as a linear problem: one
    /// Gauss-Newton step gives the closed form of Press et al. (Numerical Recipes, 3rd
    /// ed., eqs 15.2.6 and 15.2.9), a = (Sxx Sy - Sx Sxy) / D, b = (S Sxy - Sx Sy) / D,
    /// sigma_a^2 = Sxx / D, sigma_b^2 = S / D with D = S Sxx - Sx^2, the variances scaled
    /// by chi^2 / (n - 2).
    #[test]
    fn a_weighted_line_and_its_closed_form() {
        let x = [0.5, 1.0, 1.7, 2.4, 3.0, 4.2, 5.1];
        let y = [1.9, 3.2, 4.1, 6.3, 7.0, 9.9, 11.6];
        let sigma = [0.1, 0.3, 0.2, 0.5, 0.2, 0.4, 0.6];
        let w: Vec<f64> = sigma.iter().map(|s| 1.0 / (s * s)).collect();
        let sum = |f: &dyn Fn(usize) -> f64| (0..x.len()).map(f).sum::<f64>();
        let s = sum(&|i| w[i]);
        let sx = sum(&|i| w[i] * x[i]);
        let sy = sum(&|i| w[i] * y[i]);
        let sxx = sum(&|i| w[i] * x[i] * x[i]);
        let sxy = sum(&|i| w[i] * x[i] * y[i]);
        let d = s * sxx - sx * sx;
        let (a, b) = ((sxx * sy - sx * sxy) / d, (s * sxy - sx * sy) / d);
        let chi2 = sum(&|i| w[i] * (y[i] - a - b * x[i]).powi(2));
        let scale = chi2 / (x.len() - 2) as f64;
        let (se_a, se_b) = ((scale * sxx / d).sqrt(), (scale * s / d).sqrt());
        let fit = LeastSquares::new(&["a", "b"], &[0.0, 0.0], x.len())
            .weights(&w)
            .jacobian(|_| Some(x.iter().flat_map(|&x| [1.0, x]).collect()))
            .linear()
            .solve(|p| Some(x.iter().zip(&y).map(|(x, y)| p[0] + p[1] * x - y).collect()))
            .unwrap();
        let close = |v: f64, t: f64| (v - t).abs() <= 1e-12 * t.abs();
        assert!(close(fit.params[0], a) && close(fit.params[1], b), "{:?} {a} {b}", fit.params);
        assert!(close(fit.stderr_independent[0], se_a) && close(fit.stderr_independent[1], se_b), "{fit:?}");
        assert!(close(fit.chi2, chi2), "{} {chi2}", fit.chi2);
        let cov_ab = -scale * sx / d;
        assert!(close(fit.covariance[1], cov_ab * (fit.stderr[0] / fit.stderr_independent[0]).powi(2)), "{fit:?}");
    }

    /// The 3/2 law y = a (x - c)^1.5 on exact data, from a start 20 % off, with forward
    /// differences and with the model's Jacobian: a and c to 1e-10.
    #[test]
    fn a_threshold_law_recovered_from_exact_data() {
        let (a, c) = (11.8, 0.047);
        let x: Vec<f64> = (0..10).map(|k| 0.06 + 0.05 * k as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| a * (x - c).powf(1.5)).collect();
        let residuals = |p: &[f64]| -> Option<Vec<f64>> {
            (p[1] < x[0]).then(|| x.iter().zip(&y).map(|(x, y)| p[0] * (x - p[1]).powf(1.5) - y).collect())
        };
        let derivative = |p: &[f64]| -> Option<Vec<f64>> {
            Some(x.iter().flat_map(|x| [(x - p[1]).powf(1.5), -1.5 * p[0] * (x - p[1]).sqrt()]).collect())
        };
        let start = [a * 1.2, c * 0.8];
        for fit in [
            fit(&["a", "theta_c"], &start, x.len(), residuals).unwrap(),
            LeastSquares::new(&["a", "theta_c"], &start, x.len()).jacobian(derivative).solve(residuals).unwrap(),
        ] {
            assert!((fit.params[0] - a).abs() < 1e-10 * a, "{:?}", fit.params);
            assert!((fit.params[1] - c).abs() < 1e-10 * c, "{:?}", fit.params);
            assert!(fit.rms < 1e-12, "{fit:?}");
        }
    }

    /// A nonlinear model recovered exactly from exact data, and the refusals: too few
    /// cells, two parameters that only enter as their sum, a weight that is not a
    /// number, and no convergence.
    #[test]
    fn exact_recovery_and_the_refusals() {
        let x: Vec<f64> = (1..=20).map(|k| 0.02 * k as f64).collect();
        let model = |p: &[f64], x: f64| p[0] + (p[1] - p[0]) / (p[2] / x + 1.0);
        let truth = [0.38, 0.9, 0.4];
        let y: Vec<f64> = x.iter().map(|&x| model(&truth, x)).collect();
        let s = fit(&["mu_s", "mu_2", "i0"], &[0.35, 0.97, 0.69], x.len(), |p| {
            (p[2] > 0.0).then(|| x.iter().zip(&y).map(|(&x, y)| model(p, x) - y).collect())
        })
        .unwrap();
        for (f, t) in s.params.iter().zip(truth) {
            assert!((f - t).abs() < 1e-6, "{:?}", s.params);
        }
        let e = fit(&["a", "b"], &[0.0, 0.0], 4, |_| Some(vec![0.0; 4])).unwrap_err();
        assert!(e.starts_with("too few cells"), "{e}");
        let noisy: Vec<f64> = (0..10).map(|k| 1.0 + 0.01 * ((k * 7 % 5) as f64 - 2.0)).collect();
        let e =
            fit(&["a", "b"], &[0.5, 0.2], 10, |p| Some(noisy.iter().map(|y| p[0] + p[1] - y).collect())).unwrap_err();
        assert!(e.starts_with("singular regression"), "{e}");
        let w = [1.0, f64::NAN, 1.0, 1.0, 1.0];
        let e = LeastSquares::new(&["a"], &[0.0], 5).weights(&w).solve(|p| Some(vec![p[0] - 1.0; 5])).unwrap_err();
        assert!(e.contains("weight of point 1"), "{e}");
        // r = 1/p has its infimum at p -> infinity: each step doubles p and never shrinks
        let e = fit(&["p"], &[1.0], 5, |p| (p[0] > 0.0).then(|| vec![1.0 / p[0]; 5])).unwrap_err();
        assert!(e.starts_with("no convergence"), "{e}");
    }
}
