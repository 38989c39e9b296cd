//! The layer where the grains move, and the shaping of the profiles the moving-layer RMS
//! of `precision.csv` compares there: Fry et al. 2024's eq-11 Gaussian (`smooth`) and the
//! distance above each profile's bed surface (`align`), the same 1 %-of-the-flux level the
//! runs' summaries give as their bed surface.

use std::borrow::Cow;

use saltus_solvers::measures::flux_levels::flux_levels;
use saltus_solvers::Profiles;

use crate::eval::cell_widths;
use crate::table::Table;

/// Profile columns whose RMS difference over the moving layer the table gives.
pub const MOVING: [&str; 2] = ["phi", "u_p"];

/// Rows of the reference where the grains move: phi above this (no clear fluid, where a
/// DEM's u_p is undefined)...
pub const MOVING_PHI: f64 = 0.01;

/// ...and u_p above this fraction of the largest u_p of those rows (no creeping bed).
pub const MOVING_U_P: f64 = 0.05;

/// Largest `smooth` (grain diameters): beyond it the Gaussian spans any bed of the scenes.
pub const MAX_SMOOTH: f64 = 100.0;

/// Reach of the smoothing Gaussian, in h_g: exp(-5^2) = 1.4e-11.
const GAUSS_REACH: f64 = 5.0;

/// Fraction of a profile's flux that flows below its bed surface (`align`).
pub const BED_FLUX: f64 = 0.01;

/// Indices of the rows where the grains move: phi above [`MOVING_PHI`] and u_p above
/// [`MOVING_U_P`] of the largest u_p among the grains (an Eulerian reference's u_p is
/// defined in the clear fluid too, where it can exceed the layer's).
pub(crate) fn moving_rows(z: &[f64], phi: &[f64], u_p: &[f64]) -> Vec<usize> {
    let n = z.len().min(phi.len()).min(u_p.len());
    let top = (0..n).filter(|&k| phi[k] > MOVING_PHI && u_p[k].is_finite()).fold(0.0f64, |m, k| m.max(u_p[k]));
    (0..n).filter(|&k| phi[k] > MOVING_PHI && u_p[k] > MOVING_U_P * top && top > 0.0).collect()
}

/// The rows of `reference` where the grains move ([`moving_rows`]), with its z, phi and
/// u_p; `None` without those columns or without such a row.
pub(super) fn layer(reference: &Table) -> Option<Table> {
    let (z, phi, u_p) = (reference.get("z")?, reference.get("phi")?, reference.get("u_p")?);
    let keep = moving_rows(z, phi, u_p);
    if keep.is_empty() {
        return None;
    }
    let mut t = Table::default();
    for (name, col) in [("z", z), ("phi", phi), ("u_p", u_p)] {
        t.push(name, keep.iter().map(|&k| col[k]).collect());
    }
    Some(t)
}

/// `p` as the moving-layer RMS takes it: itself when neither smoothed (`h_g` 0) nor
/// aligned, else [`prepared`].
pub(super) fn shaped(p: &Profiles, h_g: f64, align: bool) -> Option<Cow<'_, Profiles>> {
    if h_g > 0.0 || align {
        prepared(p, h_g, align).map(Cow::Owned)
    } else {
        Some(Cow::Borrowed(p))
    }
}

/// z, phi and u_p of `p` for the moving-layer RMS: phi and the flux phi u_p weighted with
/// Fry et al. 2024's eq-11 Gaussian exp(-((z - z')/h_g)^2) of width `h_g` (m; none when 0),
/// normalised over the column and by the cells' widths, u_p their ratio (the run's own
/// where no grain is); z taken from the bed surface (the level below which [`BED_FLUX`] of
/// the flux flows, as the summaries' bed surface) when `align`. `None` without z, phi and
/// u_p, with z that are not increasing cell centres, or, when aligned, without a flux.
pub(crate) fn prepared(p: &Profiles, h_g: f64, align: bool) -> Option<Profiles> {
    let (z, phi, u_p) = (p.get("z")?, p.get("phi")?, p.get("u_p")?);
    let n = z.len();
    if n == 0 || phi.len() != n || u_p.len() != n {
        return None;
    }
    let dz = cell_widths(z, "profiles").ok()?;
    let finite = |v: f64| if v.is_finite() { v } else { 0.0 };
    let mut phi_s: Vec<f64> = phi.iter().map(|&v| finite(v)).collect();
    let mut flux: Vec<f64> = (0..n).map(|k| phi_s[k] * finite(u_p[k])).collect();
    if h_g > 0.0 {
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            // beyond GAUSS_REACH h_g a weight is below 1e-10 of the centre's: summing the
            // cells within reach keeps a column of many cells linear in its length
            let lo = z.partition_point(|&v| v < z[k] - GAUSS_REACH * h_g);
            let hi = z.partition_point(|&v| v <= z[k] + GAUSS_REACH * h_g);
            let (mut w_sum, mut pa, mut fb) = (0.0, 0.0, 0.0);
            for j in lo..hi {
                let w = (-((z[k] - z[j]) / h_g).powi(2)).exp() * dz[j];
                w_sum += w;
                pa += w * phi_s[j];
                fb += w * flux[j];
            }
            if w_sum > 0.0 {
                a[k] = pa / w_sum;
                b[k] = fb / w_sum;
            }
        }
        phi_s = a;
        flux = b;
    }
    // where no grain is (after smoothing), the run's own u_p: a continuum's is defined there
    let u: Vec<f64> = (0..n).map(|k| if phi_s[k] > 1e-9 { flux[k] / phi_s[k] } else { finite(u_p[k]) }).collect();
    let shift = if align {
        let faces: Vec<f64> = std::iter::once(0.0)
            .chain(dz.iter().scan(0.0, |top, w| Some(std::mem::replace(top, *top + w) + w)))
            .collect();
        Some(flux_levels(&faces, &flux, BED_FLUX, BED_FLUX).0).filter(|v| v.is_finite())?
    } else {
        0.0
    };
    let mut out = Profiles::default();
    out.push("z", z.iter().map(|v| v - shift).collect());
    out.push("phi", phi_s);
    out.push("u_p", u);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::precision::{rows, ReferenceSpec};
    use saltus_solvers::{RunReport, Summary};

    /// The moving-layer RMS sees only the rows where the reference's grains move: a run
    /// that differs in the clear fluid (phi <= 0.01) and in the creeping bed (u_p <= 5 %
    /// of the largest) has none, one that differs inside the layer has its difference.
    #[test]
    fn the_moving_layer_leaves_out_the_clear_fluid_and_the_creeping_bed() {
        let profiles = |phi: Vec<f64>, u_p: Vec<f64>| {
            let mut p = Profiles::default();
            p.push("z", vec![0.0, 1.0, 2.0, 3.0, 4.0]);
            p.push("phi", phi);
            p.push("u_p", u_p);
            RunReport {
                summary: Summary { qs_star: Some(1.0), ..Summary::default() },
                profiles: p,
                text: String::new(),
            }
        };
        // bed (creeping), two moving rows, clear fluid
        let dem = profiles(vec![0.6, 0.6, 0.4, 0.1, 0.0], vec![0.001, 0.04, 0.5, 1.0, 2.0]);
        let outside = profiles(vec![0.55, 0.6, 0.4, 0.1, 0.05], vec![0.03, 0.04, 0.5, 1.0, 0.0]);
        let inside = profiles(vec![0.6, 0.6, 0.43, 0.1, 0.0], vec![0.001, 0.04, 0.5, 0.9, 2.0]);
        let spec = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let rows =
            rows(&spec, &[("dem", Some(&dem)), ("outside", Some(&outside)), ("inside", Some(&inside))], &[], 1.0);
        // the largest u_p among the grains is 1.0 (the clear fluid's 2.0 is not counted):
        // rows 2 and 3 move, row 1 (0.04) creeps
        assert_eq!(rows[0].moving_rms, [Some(0.0), Some(0.0)]);
        assert!(rows[1].rms[0].unwrap() > 0.0 && rows[1].rms[1].unwrap() > 0.0, "{:?}", rows[1]);
        assert_eq!(rows[1].moving_rms, [Some(0.0), Some(0.0)]);
        // rows 2 and 3 move: differences 0.03 and 0 in phi, 0 and 0.1 in u_p
        let m = rows[2].moving_rms;
        assert!((m[0].unwrap() - 0.03 / 2f64.sqrt()).abs() < 1e-12, "{m:?}");
        assert!((m[1].unwrap() - 0.1 / 2f64.sqrt()).abs() < 1e-12, "{m:?}");
    }

    /// Centres of `n` even cells over `height`.
    fn centres(n: usize, height: f64) -> Vec<f64> {
        (0..n).map(|k| (k as f64 + 0.5) * height / n as f64).collect()
    }

    fn column(z: &[f64], phi: Vec<f64>, u_p: Vec<f64>) -> RunReport {
        let mut p = Profiles::default();
        p.push("z", z.to_vec());
        p.push("phi", phi);
        p.push("u_p", u_p);
        RunReport { summary: Summary { qs_star: Some(1.0), ..Summary::default() }, profiles: p, text: String::new() }
    }

    /// Grains stacked in layers one diameter apart (phi 0.3 +- 0.1 sin(2 pi z / d) over the
    /// middle of the column, tapered to an even 0.3 towards its ends) against a continuum's
    /// even 0.3: the layers are the whole difference, RMS 0.1 / sqrt 2 where they are full. Fry's Gaussian
    /// of h_g = d damps a wave of length d by exp(-pi^2) = 5.2e-5, so with `smooth = 1` the
    /// difference all but vanishes (what is left comes from the taper).
    #[test]
    fn smoothing_over_a_diameter_takes_out_the_grain_layers() {
        let d = 1e-3;
        let n = 800;
        let z = centres(n, 20.0 * d);
        let taper = |z: f64| {
            let x = ((z / d - 4.0) / 4.0).clamp(0.0, 1.0).min(((16.0 - z / d) / 4.0).clamp(0.0, 1.0));
            (0.5 - 0.5 * (std::f64::consts::PI * x).cos()).powi(2)
        };
        let layered: Vec<f64> =
            z.iter().map(|&z| 0.3 + 0.1 * taper(z) * (2.0 * std::f64::consts::PI * z / d).sin()).collect();
        let dem = column(&z, layered, vec![1.0; n]);
        let even = column(&z, vec![0.3; n], vec![1.0; n]);
        let runs = [("dem", Some(&dem)), ("continuum", Some(&even))];
        let plain = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let raw = rows(&plain, &runs, &[], d)[1].moving_rms[0].unwrap();
        // the layers are full over 4 d of the 20 d, rise over 4 d on either side, and are
        // absent from the 4 d at each end
        assert!(raw > 0.03 && raw < 0.1 / 2f64.sqrt(), "{raw}");
        let smoothed = ReferenceSpec { smooth: Some(1.0), ..plain };
        let s = rows(&smoothed, &runs, &[], d)[1].moving_rms[0].unwrap();
        // the taper's own rise leaks a little through the Gaussian: below 1 % of the layers
        assert!(s < 1e-2 * raw, "{s} against {raw}");
        // the layers are not in u_p: its difference stays zero either way
        assert!(rows(&smoothed, &runs, &[], d)[1].moving_rms[1].unwrap() < 1e-12);
    }

    /// The same moving layer standing 0.7 d higher (a looser deposit): at the same height
    /// it differs by a large part of phi, against the distance above each bed surface it
    /// does not.
    #[test]
    fn aligned_profiles_do_not_count_a_higher_bed_as_a_difference() {
        let d = 1e-3;
        let n = 400;
        let z = centres(n, 20.0 * d);
        let layer = |shift: f64| {
            let phi: Vec<f64> = z.iter().map(|&z| 0.3 * (1.0 - ((z - 8.0 * d - shift) / d).tanh())).collect();
            let u: Vec<f64> = z.iter().map(|&z| 0.05 * (1.0 + ((z - 8.0 * d - shift) / d).tanh())).collect();
            column(&z, phi, u)
        };
        let (dem, higher) = (layer(0.0), layer(0.7 * d));
        let runs = [("dem", Some(&dem)), ("higher", Some(&higher))];
        let plain = ReferenceSpec { variant: Some("dem".into()), ..ReferenceSpec::default() };
        let at_height = rows(&plain, &runs, &[], d)[1].moving_rms;
        let aligned = ReferenceSpec { align: true, ..plain };
        let from_bed = rows(&aligned, &runs, &[], d)[1].moving_rms;
        assert!(at_height[0].unwrap() > 0.1, "{at_height:?}");
        // interpolation between cells of d/20 only
        assert!(from_bed[0].unwrap() < 1e-3 && from_bed[1].unwrap() < 1e-4, "{from_bed:?}");
    }

    /// An even flux over cells of 0.1 from the bottom wall: 1 % of it flows below 1 % of
    /// the column's height, and `align` takes z from there.
    #[test]
    fn the_bed_surface_is_where_one_percent_of_the_flux_flows_below() {
        let z: Vec<f64> = (0..10).map(|k| 0.05 + 0.1 * k as f64).collect();
        let shifted = |phi: Vec<f64>| {
            let mut p = Profiles::default();
            p.push("z", z.clone());
            p.push("phi", phi);
            p.push("u_p", vec![2.0; 10]);
            prepared(&p, 0.0, true).map(|q| q.get("z").map(|v| z[0] - v[0]).unwrap_or(f64::NAN))
        };
        let level = shifted(vec![0.5; 10]).unwrap();
        assert!((level - 0.01).abs() < 1e-12, "{level}");
        // grains only in the top three cells: 1 % of their flux is 0.03 of the way into the eighth
        let mut phi = vec![0.0; 10];
        phi[7..].fill(0.5);
        assert!((shifted(phi).unwrap() - 0.703).abs() < 1e-12);
        // no flux, or no number, gives no surface to align on
        assert_eq!(shifted(vec![0.0; 10]), None);
        assert_eq!(shifted(vec![f64::NAN; 10]), None);
    }
}
