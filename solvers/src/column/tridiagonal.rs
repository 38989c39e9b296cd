//! Thomas algorithm (tridiagonal double sweep) on preallocated storage.

/// A tridiagonal system A x = r of fixed size with its storage, allocated once and reused
/// every solve (no allocation inside [`Tridiagonal::solve`]).
///
/// Row i reads `lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i]`; `lower[0]` and
/// `upper[n-1]` are ignored.
///
/// Stability: the Thomas algorithm performs Gaussian elimination without pivoting. It is
/// stable (the modified super-diagonal |c'_i| <= 1 and no pivot vanishes) when A is
/// diagonally dominant, |diag_i| >= |lower_i| + |upper_i| with strict inequality in at
/// least one row of an irreducible matrix, or symmetric positive definite. The column
/// momentum operator is such an M-matrix: the time and drag terms add to the diagonal
/// only, the diffusive conductances are non-negative, and the no-slip wall row is strictly
/// dominant. A zero or non-finite pivot (which cannot occur for such systems) is reported
/// as an error with the row instead of producing infinities.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Tridiagonal {
    /// sub-diagonal (index i multiplies x[i-1])
    pub lower: Vec<f64>,
    /// diagonal
    pub diag: Vec<f64>,
    /// super-diagonal (index i multiplies x[i+1])
    pub upper: Vec<f64>,
    /// right-hand side
    pub rhs: Vec<f64>,
    /// scratch of the forward sweep (modified super-diagonal)
    scratch: Vec<f64>,
}

impl Tridiagonal {
    /// System of `n` rows, all coefficients zero.
    pub fn new(n: usize) -> Self {
        Self { lower: vec![0.0; n], diag: vec![0.0; n], upper: vec![0.0; n], rhs: vec![0.0; n], scratch: vec![0.0; n] }
    }

    /// Number of rows.
    #[inline]
    pub fn len(&self) -> usize {
        self.diag.len()
    }

    /// Whether the system has no row.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.diag.is_empty()
    }

    /// Solve into `x` (length n). The coefficients are left untouched. On a zero or
    /// non-finite pivot, returns `Err(row)`; `x` is then unspecified.
    pub fn solve(&mut self, x: &mut [f64]) -> Result<(), usize> {
        thomas(&self.lower, &self.diag, &self.upper, &self.rhs, &mut self.scratch, x)
    }
}

/// Thomas algorithm on slices of equal length n: forward elimination then back
/// substitution, 8n flops. `scratch` (length n) holds the modified super-diagonal; the
/// solution goes to `x`. See [`Tridiagonal`] for the stability conditions. Returns
/// `Err(row)` on a zero or non-finite pivot, or `Err(0)` when the lengths differ.
pub fn thomas(
    lower: &[f64],
    diag: &[f64],
    upper: &[f64],
    rhs: &[f64],
    scratch: &mut [f64],
    x: &mut [f64],
) -> Result<(), usize> {
    let n = diag.len();
    if lower.len() != n || upper.len() != n || rhs.len() != n || scratch.len() != n || x.len() != n {
        return Err(0);
    }
    if n == 0 {
        return Ok(());
    }
    let mut pivot = diag[0];
    if pivot == 0.0 || !pivot.is_finite() {
        return Err(0);
    }
    scratch[0] = upper[0] / pivot;
    x[0] = rhs[0] / pivot;
    for i in 1..n {
        pivot = diag[i] - lower[i] * scratch[i - 1];
        if pivot == 0.0 || !pivot.is_finite() {
            return Err(i);
        }
        scratch[i] = upper[i] / pivot;
        x[i] = (rhs[i] - lower[i] * x[i - 1]) / pivot;
    }
    for i in (0..n - 1).rev() {
        x[i] -= scratch[i] * x[i + 1];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_dominant_system() {
        let n = 7;
        let mut t = Tridiagonal::new(n);
        let exact: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin() + 2.0).collect();
        for i in 0..n {
            t.lower[i] = if i > 0 { -1.0 - 0.1 * i as f64 } else { 0.0 };
            t.upper[i] = if i + 1 < n { -0.5 } else { 0.0 };
            t.diag[i] = 3.0 + i as f64;
        }
        for i in 0..n {
            let mut r = t.diag[i] * exact[i];
            if i > 0 {
                r += t.lower[i] * exact[i - 1];
            }
            if i + 1 < n {
                r += t.upper[i] * exact[i + 1];
            }
            t.rhs[i] = r;
        }
        let mut x = vec![0.0; n];
        t.solve(&mut x).unwrap();
        for (a, b) in x.iter().zip(&exact) {
            assert!((a - b).abs() < 1e-14 * b.abs());
        }
    }

    #[test]
    fn zero_pivot_is_an_error() {
        let mut t = Tridiagonal::new(3);
        t.diag.copy_from_slice(&[1.0, 1.0, 1.0]);
        t.lower[1] = 1.0;
        t.upper[0] = 1.0;
        let mut x = vec![0.0; 3];
        assert_eq!(t.solve(&mut x), Err(1));
        assert_eq!(thomas(&[0.0], &[1.0], &[0.0], &[1.0], &mut [0.0; 2], &mut [0.0]), Err(0));
    }
}
