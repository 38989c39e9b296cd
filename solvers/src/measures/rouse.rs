//! The Rouse number of a concentration profile, fitted as Cheng, Chauchat, Hsu & Calantoni
//! do (eqs 38-39), one definition for the reports of both solvers.
//!
//! phi / phi_r = [((z - z_b) / (h + z_b - z)) ((h + z_b - z_r) / (z_r - z_b))]^(-Ro)
//! (eq 39; eq 38 is z_b = 0), with the reference level z_r = z_b + 0.1 h (Cheng section 3.1:
//! the lowest level where the Reynolds stress of the channel is linear).
//!
//! Decisions:
//! * Fitting range z_r <= z <= z_b + h/2: the lower half of the flow, where both the
//!   Rouse assumptions (linear stress, parabolic eddy viscosity) and Cheng's k-omega
//!   channel hold; the symmetry plane (or free surface) of a k-omega column keeps a finite
//!   eddy viscosity, so the upper half leaves the parabolic form on which eq 38 rests.
//! * Two-parameter least squares of ln(phi) = ln(phi_r) - Ro ln(X) over the cell centres of
//!   the range, weighted by the cell heights (so that the fit does not depend on the
//!   stretching of the grid); phi_r is fitted, not read off one cell.
//! * Undefined (`None`) when fewer than three centres lie in the range or any of their phi
//!   is not positive and finite (no suspension to fit).

/// Fraction of the depth at which the reference level z_r lies (Cheng section 3.1).
pub const REFERENCE_FRACTION: f64 = 0.1;
/// Upper end of the fitting range, as a fraction of the depth.
pub const TOP_FRACTION: f64 = 0.5;

/// Rouse number fitted to the profile `phi` at the cell centres `z` (heights `dz`) of a
/// flow of depth `h` above the bed level `z_b`.
pub fn rouse_number(z: &[f64], dz: &[f64], phi: &[f64], z_b: f64, h: f64) -> Option<f64> {
    if !(h > 0.0 && h.is_finite() && z_b.is_finite()) {
        return None;
    }
    let z_r = z_b + REFERENCE_FRACTION * h;
    let z_top = z_b + TOP_FRACTION * h;
    let scale = (h + z_b - z_r) / (z_r - z_b);
    let (mut sw, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut count = 0;
    for ((&zi, &w), &p) in z.iter().zip(dz).zip(phi) {
        if zi < z_r || zi > z_top {
            continue;
        }
        if !(p > 0.0 && p.is_finite()) {
            return None;
        }
        let x = ((zi - z_b) / (h + z_b - zi) * scale).ln();
        let y = p.ln();
        sw += w;
        sx += w * x;
        sy += w * y;
        sxx += w * x * x;
        sxy += w * x * y;
        count += 1;
    }
    if count < 3 {
        return None;
    }
    let var = sxx - sx * sx / sw;
    let cov = sxy - sx * sy / sw;
    let ro = -cov / var;
    (var > 0.0 && ro.is_finite()).then_some(ro)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn grid(n: usize, z_b: f64, h: f64) -> (Vec<f64>, Vec<f64>) {
        let dz = h / n as f64;
        ((0..n).map(|i| z_b + (i as f64 + 0.5) * dz).collect(), vec![dz; n])
    }

    #[test]
    fn recovers_the_exponent_of_an_exact_rouse_profile() {
        for (z_b, h, ro) in [(0.0, 0.02, 1.44), (0.04, 0.128, 0.86), (0.0, 0.1, 0.307)] {
            let (z, dz) = grid(200, z_b, h);
            let z_r = z_b + 0.1 * h;
            let phi: Vec<f64> = z
                .iter()
                .map(|&zi| 3e-4 * ((zi - z_b) / (h + z_b - zi) * (h + z_b - z_r) / (z_r - z_b)).powf(-ro))
                .collect();
            assert_relative_eq!(rouse_number(&z, &dz, &phi, z_b, h).unwrap(), ro, max_relative = 1e-10);
        }
    }

    #[test]
    fn undefined_without_suspension_or_range() {
        let (z, dz) = grid(100, 0.0, 0.02);
        let mut phi = vec![1e-4; 100];
        // uniform: Ro = 0
        assert!(rouse_number(&z, &dz, &phi, 0.0, 0.02).unwrap().abs() < 1e-12);
        phi[30] = 0.0;
        assert_eq!(rouse_number(&z, &dz, &phi, 0.0, 0.02), None);
        phi[30] = f64::NAN;
        assert_eq!(rouse_number(&z, &dz, &phi, 0.0, 0.02), None);
        let (z, dz) = grid(4, 0.0, 0.02);
        assert_eq!(rouse_number(&z, &dz, &[1e-4; 4], 0.0, 0.02), None);
        assert_eq!(rouse_number(&z, &dz, &[1e-4; 4], 0.0, 0.0), None);
    }
}
