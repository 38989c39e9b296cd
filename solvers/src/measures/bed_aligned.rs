//! The bed-aligned comparison of a sheet-flow profile with measured profiles,
//! one definition for the tests and the `saltus compare` table, and the interpolation
//! and RMS difference that the table's unshifted differences use too.
//!
//! A continuum model and an experiment rarely put the packed bed at the same level: the
//! model's bed settles at the packing of its rheology, the measured origin is where the
//! instrument saw the bed. The run is therefore shifted rigidly so that its bed surface,
//! the first level above the packed bed where phi falls to half its bed value (the value
//! at the bottom, linearly interpolated between centres), sits on the data's; then the
//! RMS difference is taken at the data points.
//!
//! Decisions:
//! * Half the bed value, not a fixed phi: the data pack at 0.55, the models at 0.55-0.61,
//!   and a fixed threshold would sit at different depths of their sheets.
//! * The run's profile is interpolated linearly at each data level and held constant
//!   beyond its first and last centre (the data lie inside the column in practice).
//! * Undefined (`None`) when either profile has no such level or no data point remains.

/// First level above the packed bed where `phi` (at the levels `z`, increasing) falls to
/// half its bed value `phi[0]`, linearly interpolated; `None` if it never does.
pub fn half_bed_level(z: &[f64], phi: &[f64]) -> Option<f64> {
    let half = 0.5 * phi.first()?;
    if !(half > 0.0 && half.is_finite()) {
        return None;
    }
    (1..z.len().min(phi.len()))
        .find(|&j| phi[j] < half && phi[j - 1] >= half)
        .map(|j| z[j - 1] + (half - phi[j - 1]) / (phi[j] - phi[j - 1]) * (z[j] - z[j - 1]))
}

/// `f` (at the increasing levels `z`) interpolated linearly at `at`, held constant beyond
/// the ends.
pub fn interpolate(z: &[f64], f: &[f64], at: f64) -> f64 {
    let n = z.len().min(f.len());
    if n == 0 {
        return f64::NAN;
    }
    if at <= z[0] {
        return f[0];
    }
    if at >= z[n - 1] {
        return f[n - 1];
    }
    let j = z[..n].partition_point(|&c| c < at);
    let t = (at - z[j - 1]) / (z[j] - z[j - 1]);
    f[j - 1] * (1.0 - t) + f[j] * t
}

/// Shift (m) that puts the run's bed surface (`z`, `phi`) on the data's (`data_z`,
/// `data_phi`): a data level zeta is compared with the run at zeta + shift.
pub fn shift(z: &[f64], phi: &[f64], data_z: &[f64], data_phi: &[f64]) -> Option<f64> {
    Some(half_bed_level(z, phi)? - half_bed_level(data_z, data_phi)?)
}

/// RMS difference between the run's `f` (levels `z`) and the data (`data_z`, `data_f`)
/// at the data points with a finite value that `keep` accepts (by data level and value),
/// each compared at its level plus `shift` through [`interpolate`], with the number of
/// points used; points where the run's value is not finite are left out.
pub fn rms(
    z: &[f64],
    f: &[f64],
    data_z: &[f64],
    data_f: &[f64],
    shift: f64,
    keep: impl Fn(f64, f64) -> bool,
) -> Option<(f64, usize)> {
    let (mut sum, mut count) = (0.0, 0usize);
    for (&zd, &fd) in data_z.iter().zip(data_f) {
        if !(fd.is_finite() && keep(zd, fd)) {
            continue;
        }
        let got = interpolate(z, f, zd + shift);
        if got.is_finite() {
            sum += (got - fd).powi(2);
            count += 1;
        }
    }
    (count > 0).then(|| ((sum / count as f64).sqrt(), count))
}

/// The bed-aligned metric of a run against the Revil-Baudard data: (shift (m), RMS phi over
/// the data points with phi > 0, RMS velocity over every velocity point). `u` is the
/// run's fluid velocity, compared with the measured (ACVP) velocity.
pub struct Aligned {
    /// run level minus data level of the bed surface (m)
    pub shift: f64,
    /// RMS phi over the data points with phi > 0, and their number
    pub phi: (f64, usize),
    /// RMS velocity over every data point (m/s), and their number
    pub u: Option<(f64, usize)>,
}

/// [`Aligned`] of a run (`z`, `phi`, `u`) against the concentration data (`data_z`,
/// `data_phi`) and the velocity data (`u_data`: levels and values, in the same frame).
pub fn aligned(
    z: &[f64],
    phi: &[f64],
    u: &[f64],
    data_z: &[f64],
    data_phi: &[f64],
    u_data: Option<(&[f64], &[f64])>,
) -> Option<Aligned> {
    let s = shift(z, phi, data_z, data_phi)?;
    let phi_rms = rms(z, phi, data_z, data_phi, s, |_, p| p > 0.0)?;
    let u_rms = u_data.and_then(|(zu, fu)| rms(z, u, zu, fu, s, |_, _| true));
    Some(Aligned { shift: s, phi: phi_rms, u: u_rms })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_level_of_a_linear_drop() {
        // phi 0.6 -> 0 linearly over [0, 1]: half (0.3) at z = 0.5
        let z: Vec<f64> = (0..11).map(|k| k as f64 / 10.0).collect();
        let phi: Vec<f64> = z.iter().map(|z| 0.6 * (1.0 - z)).collect();
        assert!((half_bed_level(&z, &phi).expect("level") - 0.5).abs() < 1e-12);
        assert!(half_bed_level(&z, &[0.0; 11]).is_none());
        assert!(half_bed_level(&z, &[0.5; 11]).is_none());
    }

    #[test]
    fn a_rigidly_shifted_profile_has_zero_error() {
        // the data are the run moved down by 0.013: shift 0.013, both RMS zero
        let z: Vec<f64> = (0..200).map(|k| k as f64 * 1e-3).collect();
        let phi: Vec<f64> = z.iter().map(|z| 0.55 / (1.0 + ((z - 0.05) / 0.004).exp())).collect();
        let u: Vec<f64> = z.iter().map(|z| (z - 0.04).max(0.0) * 5.0).collect();
        let dz: Vec<f64> = (0..60).map(|k| k as f64 * 1.5e-3).collect();
        let dphi: Vec<f64> = dz.iter().map(|z| 0.55 / (1.0 + ((z + 0.013 - 0.05) / 0.004).exp())).collect();
        let du: Vec<f64> = dz.iter().map(|z| (z + 0.013 - 0.04).max(0.0) * 5.0).collect();
        let a = aligned(&z, &phi, &u, &dz, &dphi, Some((&dz, &du))).expect("aligned");
        assert!((a.shift - 0.013).abs() < 1e-4, "{}", a.shift);
        assert!(a.phi.0 < 2e-3 && a.u.expect("u").0 < 2e-3, "{} {:?}", a.phi.0, a.u);
        // a uniform 0.1 m/s offset in the data is the velocity RMS
        let du2: Vec<f64> = du.iter().map(|v| v + 0.1).collect();
        let b = aligned(&z, &phi, &u, &dz, &dphi, Some((&dz, &du2))).expect("aligned");
        assert!((b.u.expect("u").0 - 0.1).abs() < 2e-3);
    }
}
