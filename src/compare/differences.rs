//! Differences between a run's profiles and reference data, for the comparison table.
//!
//! The run's profile is interpolated linearly in z at each reference row inside the span of
//! its cell centres, by the interpolation and RMS of
//! [`saltus_solvers::measures::bed_aligned`] (the bed-aligned metric's, here without a
//! shift); rows outside are skipped (no extrapolation). For particle-phase
//! columns (`u_p`, `theta_g`) a reference value of exactly 0 means "no grains, no data" (the
//! DEM files write 0 above the granular layer) and the row is skipped.

use saltus_solvers::measures::bed_aligned;
use saltus_solvers::Profiles;

use crate::table::Table;

/// Profile columns that reference data can be compared against, in table order.
pub const COMPARED: [&str; 4] = ["phi", "u_p", "u_f", "theta_g"];

/// Root-mean-square difference of column `name` between `run` and `reference` with the
/// number of reference rows used, or `None` when either lacks the column or no row lies
/// inside the run's z span.
pub fn rms_difference(run: &Profiles, reference: &Table, name: &str) -> Option<(f64, usize)> {
    let (zc, f) = (run.get("z")?, run.get(name)?);
    let (zr, fr) = (reference.get("z")?, reference.get(name)?);
    let particle = matches!(name, "u_p" | "theta_g");
    let (lo, hi) = (*zc.first()?, *zc.last()?);
    let inside = |z: f64, want: f64| z >= lo && z <= hi && !(particle && want == 0.0);
    bed_aligned::rms(zc, f, zr, fr, 0.0, inside)
}

/// Columns of the bed-aligned metric of the sheet flows (`saltus_solvers::measures::bed_aligned`), written
/// after the `rms_` columns when the reference data have a `phi` column with a packed bed:
/// the shift of the run onto the data's bed surface (m), the RMS phi over the reference rows
/// with phi > 0, the RMS of the run's `u_f` against the reference velocity (its `u_f`
/// column, else its `u_p` column: the ACVP velocity of the Revil-Baudard data, which the
/// metric compares with the fluid velocity), and the run's velocity at the top cell.
pub const ALIGNED: [&str; 4] = ["bed_shift", "aligned_rms_phi", "aligned_rms_u_f", "surface_u_f"];

/// The [`ALIGNED`] values of `run` against the reference tables (each column from the first
/// table that has it); `None` when no table has `phi` with a half-bed level.
pub fn aligned(run: &Profiles, reference: &[&Table]) -> Option<[Option<f64>; 4]> {
    let phi_ref = reference.iter().find(|t| t.get("phi").is_some())?;
    let (dz, dphi) = (phi_ref.get("z")?, phi_ref.get("phi")?);
    let u_ref = ["u_f", "u_p"].iter().find_map(|c| reference.iter().find_map(|t| Some((t.get("z")?, t.get(c)?))));
    let (z, phi, u) = (run.get("z")?, run.get("phi")?, run.get("u_f")?);
    let a = bed_aligned::aligned(z, phi, u, dz, dphi, u_ref);
    let top = u.last().copied().filter(|v| v.is_finite());
    Some(match a {
        Some(a) => [Some(a.shift), Some(a.phi.0), a.u.map(|e| e.0), top],
        None => [None, None, None, top],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run() -> Profiles {
        let mut p = Profiles::default();
        p.push("z", vec![0.0, 1.0, 2.0]);
        p.push("phi", vec![0.6, 0.3, 0.0]);
        p.push("u_p", vec![0.0, 1.0, 2.0]);
        p
    }

    fn table(cols: &[(&str, Vec<f64>)]) -> Table {
        let mut t = Table::default();
        for (n, v) in cols {
            t.push(*n, v.clone());
        }
        t
    }

    #[test]
    fn identical_data_give_zero_and_offsets_give_the_offset() {
        let r = table(&[("z", vec![0.5, 1.5]), ("phi", vec![0.45, 0.15])]);
        let (e, n) = rms_difference(&run(), &r, "phi").unwrap();
        assert!(e < 1e-15 && n == 2);
        let r = table(&[("z", vec![0.5, 1.5]), ("phi", vec![0.55, 0.25])]);
        assert!((rms_difference(&run(), &r, "phi").unwrap().0 - 0.1).abs() < 1e-12);
    }

    #[test]
    fn rows_outside_the_column_and_particle_zeros_are_skipped() {
        let r = table(&[("z", vec![-1.0, 0.5, 1.5, 3.0]), ("u_p", vec![9.0, 0.5, 0.0, 9.0])]);
        assert_eq!(rms_difference(&run(), &r, "u_p"), Some((0.0, 1)));
        assert_eq!(rms_difference(&run(), &r, "u_f"), None);
    }
}
