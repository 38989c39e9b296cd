//! Cell-centred 1D grid of the fluid column, from the bottom wall z = 0 to the top z = H.

use super::ColumnError;

/// A 1D finite-volume grid: `n` cells bounded by `n + 1` faces, the first face on the
/// bottom wall (z = 0) and the last one on the top (z = H).
///
/// Structure of arrays: faces `z_f[0..=n]`, centres `z_c[0..n]` (midpoints of their
/// faces) and widths `dz[0..n]`. Non-uniform grids are supported throughout the column
/// solver: every distance is taken from these arrays, never from a constant spacing.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Grid {
    faces: Vec<f64>,
    centres: Vec<f64>,
    dz: Vec<f64>,
}

impl Grid {
    /// Uniform grid of `n >= 2` cells over a column of height `h > 0`.
    pub fn uniform(n: usize, h: f64) -> Result<Grid, ColumnError> {
        Self::geometric(n, h, 1.0)
    }

    /// Grid whose widths grow geometrically from the wall, dz_i = dz_0 r^i with
    /// `ratio` = r > 0 (r = 1 is uniform, r > 1 refines near the bottom wall), scaled so
    /// that the widths sum to `h`.
    pub fn geometric(n: usize, h: f64, ratio: f64) -> Result<Grid, ColumnError> {
        if n < 2 {
            return Err(ColumnError::InvalidParameter {
                name: "cells",
                value: n as f64,
                reason: "the column needs at least 2 cells (second-order wall gradient)",
            });
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(ColumnError::InvalidParameter { name: "height", value: h, reason: "must be finite and > 0" });
        }
        if !(ratio.is_finite() && ratio > 0.0) {
            return Err(ColumnError::InvalidParameter {
                name: "stretching ratio",
                value: ratio,
                reason: "must be finite and > 0",
            });
        }
        let mut faces = Vec::with_capacity(n + 1);
        faces.push(0.0);
        if ratio == 1.0 {
            let d = h / n as f64;
            faces.extend((1..n).map(|i| i as f64 * d));
        } else {
            // widths r^i, normalised by their sum
            let total: f64 = (0..n).map(|i| ratio.powi(i as i32)).sum();
            let mut acc = 0.0;
            for i in 0..n - 1 {
                acc += ratio.powi(i as i32);
                faces.push(h * acc / total);
            }
        }
        faces.push(h);
        Self::from_faces(faces)
    }

    /// Grid from its faces: `faces[0] = 0` (the wall), strictly increasing and finite, at
    /// least 3 faces (2 cells).
    pub fn from_faces(faces: Vec<f64>) -> Result<Grid, ColumnError> {
        if faces.len() < 3 {
            return Err(ColumnError::InvalidParameter {
                name: "cells",
                value: faces.len().saturating_sub(1) as f64,
                reason: "the column needs at least 2 cells (second-order wall gradient)",
            });
        }
        if faces[0] != 0.0 {
            return Err(ColumnError::InvalidParameter {
                name: "faces[0]",
                value: faces[0],
                reason: "the first face is the bottom wall and must be 0",
            });
        }
        for w in faces.windows(2) {
            if !(w[1].is_finite() && w[1] > w[0]) {
                return Err(ColumnError::InvalidParameter {
                    name: "faces",
                    value: w[1],
                    reason: "faces must be finite and strictly increasing",
                });
            }
        }
        let centres = faces.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let dz = faces.windows(2).map(|w| w[1] - w[0]).collect();
        Ok(Grid { faces, centres, dz })
    }

    /// Number of cells n.
    #[inline]
    pub fn len(&self) -> usize {
        self.dz.len()
    }

    /// Always false (a grid has at least 2 cells).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.dz.is_empty()
    }

    /// Column height H (position of the top face).
    #[inline]
    pub fn height(&self) -> f64 {
        self.faces[self.faces.len() - 1]
    }

    /// Faces z_f[0..=n] (m); `z_f[0] = 0`, `z_f[n] = H`.
    #[inline]
    pub fn faces(&self) -> &[f64] {
        &self.faces
    }

    /// Cell centres z_c[0..n] (m).
    #[inline]
    pub fn centres(&self) -> &[f64] {
        &self.centres
    }

    /// Cell widths dz[0..n] (m).
    #[inline]
    pub fn dz(&self) -> &[f64] {
        &self.dz
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_and_geometric() {
        let g = Grid::uniform(4, 2.0).unwrap();
        assert_eq!(g.faces(), &[0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(g.centres(), &[0.25, 0.75, 1.25, 1.75]);
        assert_eq!(g.dz(), &[0.5; 4]);
        let s = Grid::geometric(50, 1.0, 1.1).unwrap();
        assert_eq!(s.height(), 1.0);
        for w in s.dz().windows(2) {
            assert!((w[1] / w[0] - 1.1).abs() < 1e-9);
        }
        assert!((s.dz().iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn refuses_bad_grids() {
        assert!(Grid::uniform(1, 1.0).is_err());
        assert!(Grid::uniform(10, 0.0).is_err());
        assert!(Grid::uniform(10, f64::NAN).is_err());
        assert!(Grid::geometric(10, 1.0, -1.0).is_err());
        assert!(Grid::from_faces(vec![0.0, 1.0, 1.0]).is_err());
        assert!(Grid::from_faces(vec![0.1, 1.0, 2.0]).is_err());
        assert!(Grid::from_faces(vec![0.0, 1.0, f64::NAN]).is_err());
    }
}
