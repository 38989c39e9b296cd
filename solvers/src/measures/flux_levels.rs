//! Levels of a flux profile: the levels below which given fractions of the transport
//! flow (the bed surface, the transport layer), and the flux layer of Cheng et al.

/// Levels (m) below which the fractions `lo` and `hi` of the integral of `q dz` lie,
/// interpolated linearly inside cells.
pub fn flux_levels(faces: &[f64], q: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    flux_levels_by(q.len().min(faces.len().saturating_sub(1)), |i| faces[i], |i| q[i], lo, hi)
}

/// Threshold of the local flux phi u_p over sqrt((s - 1) g d) above which a cell is in
/// the transport layer of Cheng et al. (section 4.2).
pub const FLUX_LAYER_THRESHOLD: f64 = 0.05;

/// Total height (m) of the cells between `faces` whose flux density `q` (m/s) exceeds
/// [`FLUX_LAYER_THRESHOLD`] times `scale` = sqrt((s - 1) g d) (m/s); NaN without a scale
/// or where no cell exceeds it. Summed cell by cell rather than taken between the lowest
/// and highest such cell, so that one noisy cell of a DEM profile above the layer does not
/// count the clear water below it.
pub fn flux_layer_thickness(faces: &[f64], q: &[f64], scale: f64) -> f64 {
    if !(scale > 0.0 && scale.is_finite()) {
        return f64::NAN;
    }
    let limit = FLUX_LAYER_THRESHOLD * scale;
    let h: f64 = q.iter().zip(faces.windows(2)).filter(|(q, _)| **q > limit).map(|(_, f)| f[1] - f[0]).sum();
    if h > 0.0 {
        h
    } else {
        f64::NAN
    }
}

/// [`flux_levels`] over `n` cells with face `i` at `face(i)` and the flux density of cell
/// `i` `q(i)`: for fields that are not stored as one slice (a product of two, a uniform
/// grid), without allocating.
pub fn flux_levels_by(n: usize, face: impl Fn(usize) -> f64, q: impl Fn(usize) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    let total: f64 = (0..n).map(|i| q(i) * (face(i + 1) - face(i))).sum();
    if total.abs() <= 0.0 || !total.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let level = |frac: f64| {
        let target = frac * total;
        let mut acc = 0.0;
        for i in 0..n {
            let (a, b) = (face(i), face(i + 1));
            let add = q(i) * (b - a);
            if (acc + add) / total >= frac && add != 0.0 {
                return a + (target - acc) / add * (b - a);
            }
            acc += add;
        }
        face(n)
    };
    (level(lo), level(hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flux_levels_of_a_uniform_layer() {
        let faces: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let q = [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let (a, b) = flux_levels(&faces, &q, 0.01, 0.99);
        assert!((a - 2.04).abs() < 1e-12 && (b - 5.96).abs() < 1e-12, "{a} {b}");
    }

    /// Cheng's transport layer of a flux profile q = phi u_p: the cells above 0.05
    /// sqrt((s - 1) g d), on a stretched grid, whatever the flux does in the others.
    #[test]
    fn the_flux_layer_counts_the_cells_above_the_threshold() {
        let faces = [0.0, 1.0, 1.5, 2.5, 4.0, 4.5, 6.0];
        let scale = 2.0; // the threshold is then 0.1
        let q = [0.01, 0.2, 0.5, 0.099, 0.3, 0.05];
        let h = flux_layer_thickness(&faces, &q, scale);
        assert!((h - (0.5 + 1.0 + 0.5)).abs() < 1e-12, "{h}");
        assert!(flux_layer_thickness(&faces, &[0.0; 6], scale).is_nan());
        for bad in [0.0, f64::NAN, f64::INFINITY, -1.0] {
            assert!(flux_layer_thickness(&faces, &q, bad).is_nan());
        }
    }
}
