//! Block-tridiagonal solver with 2x2 blocks: the coupled fluid/particle streamwise
//! momentum, where drag couples the two unknowns of a cell and diffusion couples each
//! unknown with its neighbours.

/// 2x2 matrix, row-major.
pub type M2 = [[f64; 2]; 2];

fn mul(a: &M2, b: &M2) -> M2 {
    [
        [a[0][0] * b[0][0] + a[0][1] * b[1][0], a[0][0] * b[0][1] + a[0][1] * b[1][1]],
        [a[1][0] * b[0][0] + a[1][1] * b[1][0], a[1][0] * b[0][1] + a[1][1] * b[1][1]],
    ]
}

fn mulv(a: &M2, v: [f64; 2]) -> [f64; 2] {
    [a[0][0] * v[0] + a[0][1] * v[1], a[1][0] * v[0] + a[1][1] * v[1]]
}

fn inverse(a: &M2) -> Option<M2> {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let r = 1.0 / det;
    Some([[a[1][1] * r, -a[0][1] * r], [-a[1][0] * r, a[0][0] * r]])
}

/// The system lower_i x_{i-1} + diag_i x_i + upper_i x_{i+1} = rhs_i with 2x2 blocks whose
/// off-diagonal blocks are diagonal (`[f64; 2]`). Work arrays allocated once.
#[derive(Clone, Debug)]
pub struct BlockTridiagonal {
    /// diagonal of the sub-diagonal blocks (entry 0 unused)
    pub lower: Vec<[f64; 2]>,
    /// diagonal blocks
    pub diag: Vec<M2>,
    /// diagonal of the super-diagonal blocks (last entry unused)
    pub upper: Vec<[f64; 2]>,
    /// right-hand sides
    pub rhs: Vec<[f64; 2]>,
    c: Vec<M2>,
    d: Vec<[f64; 2]>,
}

impl BlockTridiagonal {
    /// Zeroed system of `n` block rows.
    pub fn new(n: usize) -> Self {
        Self {
            lower: vec![[0.0; 2]; n],
            diag: vec![[[0.0; 2]; 2]; n],
            upper: vec![[0.0; 2]; n],
            rhs: vec![[0.0; 2]; n],
            c: vec![[[0.0; 2]; 2]; n],
            d: vec![[0.0; 2]; n],
        }
    }

    /// Solve by block Gaussian elimination (block Thomas); `Err(row)` on a singular pivot.
    /// Stable without pivoting for the block diagonally dominant systems of the momentum
    /// equations.
    pub fn solve(&mut self, x: &mut [[f64; 2]]) -> Result<(), usize> {
        let n = self.diag.len();
        let diagm = |v: [f64; 2]| -> M2 { [[v[0], 0.0], [0.0, v[1]]] };
        let mut inv = inverse(&self.diag[0]).ok_or(0usize)?;
        self.c[0] = mul(&inv, &diagm(self.upper[0]));
        self.d[0] = mulv(&inv, self.rhs[0]);
        for i in 1..n {
            let l = self.lower[i];
            // B_i - A_i C_{i-1}, with A_i diagonal
            let cp = self.c[i - 1];
            let mut b = self.diag[i];
            for r in 0..2 {
                for k in 0..2 {
                    b[r][k] -= l[r] * cp[r][k];
                }
            }
            inv = inverse(&b).ok_or(i)?;
            self.c[i] = mul(&inv, &diagm(self.upper[i]));
            let dp = self.d[i - 1];
            let rhs = [self.rhs[i][0] - l[0] * dp[0], self.rhs[i][1] - l[1] * dp[1]];
            self.d[i] = mulv(&inv, rhs);
        }
        x[n - 1] = self.d[n - 1];
        for i in (0..n - 1).rev() {
            let cx = mulv(&self.c[i], x[i + 1]);
            x[i] = [self.d[i][0] - cx[0], self.d[i][1] - cx[1]];
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random block-dominant system: the solution satisfies every row.
    #[test]
    fn solves_coupled_rows() {
        let n = 7;
        let mut s = BlockTridiagonal::new(n);
        let mut state = 12345u64;
        let mut rnd = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64) / ((1u64 << 53) as f64)
        };
        for i in 0..n {
            s.lower[i] = if i > 0 { [-rnd(), -rnd()] } else { [0.0; 2] };
            s.upper[i] = if i + 1 < n { [-rnd(), -rnd()] } else { [0.0; 2] };
            let k = 5.0 * rnd();
            s.diag[i] = [[3.0 + k, -k], [-k, 3.0 + k]];
            s.rhs[i] = [rnd(), rnd()];
        }
        let (lower, diag, upper, rhs) = (s.lower.clone(), s.diag.clone(), s.upper.clone(), s.rhs.clone());
        let mut x = vec![[0.0; 2]; n];
        s.solve(&mut x).unwrap();
        for i in 0..n {
            for r in 0..2 {
                let mut v = diag[i][r][0] * x[i][0] + diag[i][r][1] * x[i][1];
                if i > 0 {
                    v += lower[i][r] * x[i - 1][r];
                }
                if i + 1 < n {
                    v += upper[i][r] * x[i + 1][r];
                }
                assert!((v - rhs[i][r]).abs() < 1e-13, "row {i}.{r}: {v} vs {}", rhs[i][r]);
            }
        }
    }

    #[test]
    fn singular_pivot_is_reported() {
        let mut s = BlockTridiagonal::new(3);
        s.diag[0] = [[1.0, 0.0], [0.0, 1.0]];
        s.diag[1] = [[1.0, 1.0], [1.0, 1.0]];
        s.diag[2] = [[1.0, 0.0], [0.0, 1.0]];
        let mut x = vec![[0.0; 2]; 3];
        assert_eq!(s.solve(&mut x), Err(1));
    }
}
