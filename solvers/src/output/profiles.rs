//! `profiles.csv`: the cell profiles of a run, and the one gradient taken of them.

use std::fmt::Write as _;

/// Named columns of equal length, written as `profiles.csv`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profiles {
    /// (name, values) in column order; the first is `z`
    pub columns: Vec<(String, Vec<f64>)>,
}

impl Profiles {
    /// Add a column.
    pub fn push(&mut self, name: &str, values: Vec<f64>) {
        self.columns.push((name.to_string(), values));
    }
    /// Column by name.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_slice())
    }
    /// CSV text with a header line. A value that is not a finite number (undefined there,
    /// e.g. the inertial number where the grains carry no pressure) is an empty cell:
    /// no `NaN` or `inf` is ever written.
    pub fn to_csv(&self) -> String {
        let mut s = self.columns.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(",");
        s.push('\n');
        let rows = self.columns.first().map_or(0, |c| c.1.len());
        for r in 0..rows {
            for (k, (_, v)) in self.columns.iter().enumerate() {
                if k > 0 {
                    s.push(',');
                }
                if v[r].is_finite() {
                    let _ = write!(s, "{:.10e}", v[r]);
                }
            }
            s.push('\n');
        }
        s
    }
}

/// d f / dz of a cell profile at its centres `z` (increasing): the central difference
/// (f[i+1] - f[i-1]) / (z[i+1] - z[i-1]) inside, one-sided at the two ends (exact for a
/// linear profile on any grid); zeros with fewer than two cells. The one gradient of
/// written profiles, so that a run's `heat_flux` and `saltus diagnose`'s -kappa dT/dz
/// difference the same way.
pub fn profile_gradient(z: &[f64], f: &[f64]) -> Vec<f64> {
    let n = z.len().min(f.len());
    if n < 2 {
        return vec![0.0; n];
    }
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (f[b] - f[a]) / (z[b] - z[a])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_of_a_linear_profile_is_exact() {
        let z = [0.1, 0.3, 0.4, 0.8];
        let f: Vec<f64> = z.iter().map(|z| 2.0 - 3.0 * z).collect();
        for g in profile_gradient(&z, &f) {
            assert!((g + 3.0).abs() < 1e-12, "{g}");
        }
        assert_eq!(profile_gradient(&[1.0], &[2.0]), vec![0.0]);
    }

    #[test]
    fn csv_has_header_and_rows() {
        let mut p = Profiles::default();
        p.push("z", vec![0.5, 1.5]);
        p.push("phi", vec![0.6, 0.0]);
        p.push("inertial_number", vec![0.1, f64::INFINITY]);
        let csv = p.to_csv();
        assert!(csv.starts_with("z,phi,inertial_number\n"));
        assert_eq!(csv.lines().count(), 3);
        assert!(csv.ends_with(",0.0000000000e0,\n"), "undefined is an empty cell: {csv}");
    }
}
