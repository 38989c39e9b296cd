//! Nonlinear least squares (Levenberg-Marquardt) with standard errors from the Jacobian,
//! for the fits of `diagnose --fit`: a few parameters, tens to hundreds of cells.
//!
//! The model is a residual function r(p) (one entry per cell) that may refuse a parameter
//! vector (`None`: outside the closure's valid range); a refused step is treated as one
//! that does not lower the sum of squares, so the fit stays inside the range.

/// A converged fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// fitted parameters
    pub params: Vec<f64>,
    /// standard errors with the cells taken as independent: sqrt(s^2 (J^T J)^-1)_ii,
    /// s^2 = SSR / (n - m)
    pub stderr_independent: Vec<f64>,
    /// the same inflated by sqrt((1 + r1) / (1 - r1)), r1 the lag-1 autocorrelation of the
    /// residuals in the order of the cells (when positive): the variance of a mean of
    /// AR(1)-correlated values, so that neighbouring cells sharing grains count less than
    /// independent ones
    pub stderr: Vec<f64>,
    /// covariance of the parameters (row-major m x m), with the inflation of `stderr`
    pub covariance: Vec<f64>,
    /// lag-1 autocorrelation of the residuals
    pub r1: f64,
    /// RMS of the residuals
    pub rms: f64,
    /// number of cells
    pub cells: usize,
}

/// Fewest cells a fit of `m` parameters takes: the parameters and three degrees of
/// freedom for the residual variance.
pub fn min_cells(m: usize) -> usize {
    m + 3
}

/// Largest |correlation| between two fitted parameters (from (J^T J)^-1) before the fit
/// is called singular: beyond it the cells determine only a combination of the two.
pub const MAX_CORRELATION: f64 = 0.999;

/// Fit `m = p0.len()` parameters from `p0` by Levenberg-Marquardt on the residuals
/// `residuals(p)` of `n` cells; the error says why the cells cannot support the fit (too
/// few cells, a singular or degenerate regression, no convergence), naming the
/// parameters by `names`.
pub fn fit(
    names: &[&str],
    p0: &[f64],
    n: usize,
    mut residuals: impl FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Result<Solution, String> {
    let m = p0.len();
    if n < min_cells(m) {
        return Err(format!("too few cells: {n} for {m} parameters (at least {} needed)", min_cells(m)));
    }
    let ssr = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut p = p0.to_vec();
    let mut r = residuals(&p).ok_or_else(|| "the starting parameters are outside the closure's range".to_string())?;
    if r.len() != n || !r.iter().all(|v| v.is_finite()) {
        return Err("the closure gives no finite value in some cell at the starting parameters".into());
    }
    let mut s = ssr(&r);
    let mut lambda = 1e-3;
    let mut converged = false;
    for _ in 0..500 {
        let j = jacobian(&p, &r, &mut residuals).ok_or("the closure's derivative is not defined at the parameters")?;
        let (a, g) = normal_equations(&j, &r, m);
        let mut stepped = false;
        while lambda < 1e12 {
            let mut damped = a.clone();
            for i in 0..m {
                damped[i * m + i] += lambda * a[i * m + i].max(1e-300);
            }
            let Some(dp) = solve(&damped, &g, m) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = p.iter().zip(&dp).map(|(x, d)| x - d).collect();
            match residuals(&trial).filter(|rt| rt.iter().all(|v| v.is_finite())) {
                Some(rt) if ssr(&rt) <= s => {
                    let s_new = ssr(&rt);
                    let small_step = dp.iter().zip(&trial).all(|(d, x)| d.abs() <= 1e-10 * (x.abs() + 1e-10));
                    let small_gain = s - s_new <= 1e-14 * s.max(1e-300);
                    p = trial;
                    r = rt;
                    s = s_new;
                    lambda = (lambda / 10.0).max(1e-12);
                    stepped = true;
                    converged = small_step || small_gain;
                    break;
                }
                _ => lambda *= 10.0,
            }
        }
        if !stepped {
            // no step lowers the sum of squares: a minimum (within round-off)
            converged = true;
        }
        if converged {
            break;
        }
    }
    if !converged {
        return Err("no convergence in 500 iterations".into());
    }
    let j =
        jacobian(&p, &r, &mut residuals).ok_or("the closure's derivative is not defined at the fitted parameters")?;
    let (a, _) = normal_equations(&j, &r, m);
    let diag: Vec<f64> = (0..m).map(|i| a[i * m + i]).collect();
    if let Some(i) = diag.iter().position(|d| d.is_nan() || *d <= 0.0) {
        return Err(format!("singular regression: the cells do not depend on `{}`", names[i]));
    }
    // the correlation form of J^T J: unit diagonal, so its conditioning is the parameters'
    let scaled: Vec<f64> = (0..m * m).map(|k| a[k] / (diag[k / m] * diag[k % m]).sqrt()).collect();
    let inv = invert(&scaled, m).ok_or("singular regression: the parameters are not separately determined")?;
    for i in 0..m {
        for k in (i + 1)..m {
            let c = inv[i * m + k] / (inv[i * m + i] * inv[k * m + k]).sqrt();
            if c.is_nan() || c.abs() >= MAX_CORRELATION {
                return Err(format!(
                    "singular regression: `{}` and `{}` are not separately determined by these cells (correlation {c:.4})",
                    names[i], names[k]
                ));
            }
        }
    }
    let s2 = s / (n - m) as f64;
    let stderr_independent: Vec<f64> = (0..m).map(|i| (s2 * inv[i * m + i] / diag[i]).sqrt()).collect();
    let r1 = lag1(&r);
    let inflation = if r1 > 0.0 { ((1.0 + r1) / (1.0 - r1).max(1e-12)).sqrt() } else { 1.0 };
    let stderr: Vec<f64> = stderr_independent.iter().map(|e| e * inflation).collect();
    let covariance: Vec<f64> =
        (0..m * m).map(|k| s2 * inflation * inflation * inv[k] / (diag[k / m] * diag[k % m]).sqrt()).collect();
    Ok(Solution { params: p, stderr_independent, stderr, covariance, r1, rms: (s / n as f64).sqrt(), cells: n })
}

/// Forward-difference Jacobian (backward where the forward point is refused), row-major
/// n x m.
fn jacobian(p: &[f64], r: &[f64], residuals: &mut impl FnMut(&[f64]) -> Option<Vec<f64>>) -> Option<Vec<f64>> {
    let (n, m) = (r.len(), p.len());
    let mut j = vec![0.0; n * m];
    for k in 0..m {
        let h = 1e-6 * p[k].abs().max(1e-3);
        let mut q = p.to_vec();
        q[k] = p[k] + h;
        let (rq, step) = match residuals(&q).filter(|v| v.iter().all(|x| x.is_finite())) {
            Some(v) => (v, h),
            None => {
                q[k] = p[k] - h;
                (residuals(&q).filter(|v| v.iter().all(|x| x.is_finite()))?, -h)
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

    /// A nonlinear model recovered exactly from exact data, and the refusals: too few
    /// cells, and two parameters that only enter as their sum.
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
    }
}
