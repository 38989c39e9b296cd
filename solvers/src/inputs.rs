//! What the closures are fed, defined once for both solvers: the flow scales of a
//! fluctuation closure (depth and bulk velocity above the bed), the Reynolds stress, and
//! the drag kernel (single-particle drag times hindrance at the hindrance's declared
//! Reynolds-number convention).

use saltus_core::{DragLaw, DragReynolds, FlowScales, Hindrance};

/// Bed surface of a column: the highest cell centre at least half as packed as the
/// densest cell, or `fallback` when no cell is packed (the densest phi is below 0.1, a
/// suspension or clear water).
pub fn bed_surface(zc: &[f64], phi: &[f64], fallback: f64) -> f64 {
    let dense = phi.iter().fold(0.0f64, |a, &b| a.max(b));
    match phi.iter().rposition(|&f| dense > 0.1 && f >= 0.5 * dense) {
        Some(c) => zc[c],
        None => fallback,
    }
}

/// Bed elevation of the peer code's DRW (Maurin's 2017 YADE script of the Frey runs,
/// `turbulentFluctuationPY`, read by `HydroForceEngine::turbulentFluctuation`): scanning
/// the cells down from the top, the lower face of the first cell c >= 1 whose solid
/// fraction exceeds `threshold` and is below that of the cell beneath it (the top of the
/// highest peak above `threshold`); 0 (the column bottom) when no cell qualifies. Heights
/// from the column bottom, cells of height `dz`.
pub fn peak_bed_elevation(phi: &[f64], dz: f64, threshold: f64) -> f64 {
    (1..phi.len()).rev().find(|&c| phi[c] > threshold && phi[c] < phi[c - 1]).map_or(0.0, |c| c as f64 * dz)
}

/// Flow scales of a fluctuation closure (Chassagne et al. 2023 eqs 4.3-4.4: the eddy
/// turnover time of the depth and the bulk velocity): the fluid depth above the bed
/// surface `bed` (m) of a column of height `height`, and the mean fluid velocity of the
/// cells above it, weighted by their heights (0 when no cell is above it).
pub fn flow_scales(zc: &[f64], dz: &[f64], u: &[f64], height: f64, bed: f64) -> FlowScales {
    let (mut q, mut depth) = (0.0, 0.0);
    for ((&z, &h), &v) in zc.iter().zip(dz).zip(u) {
        if z > bed {
            q += v * h;
            depth += h;
        }
    }
    FlowScales { depth: height - bed, bulk_velocity: if depth > 0.0 { q / depth } else { 0.0 } }
}

/// The slip magnitude of the column's mean flow that the drag closures take (m/s),
/// |(u_f - u_p, w_p / (1 - phi))|: the streamwise slip and the wall-normal one, the fluid's
/// wall-normal velocity being -phi w_p / (1 - phi) in a column with an impermeable
/// bottom (Chassagne et al. 2023 eqs 2.5-2.6 and 4.3). The Eulerian drag and `saltus
/// diagnose` evaluate it here, so that a comparison sees the solver's own slip.
#[inline]
pub fn mean_slip(u_f: f64, u_p: f64, w_p: f64, phi: f64) -> f64 {
    (u_f - u_p).hypot(w_p / (1.0 - phi))
}

/// Kinematic Reynolds shear stress R_xz / (rho_f eps) = nu_t |du/dz| (m^2/s^2) of a
/// mixing-length or two-equation column, the magnitude a fluctuation closure scales with
/// (Chassagne et al. 2023 eq 4.4); its sign does not enter.
#[inline]
pub fn reynolds_stress(nu_t: f64, shear_rate: f64) -> f64 {
    nu_t * shear_rate.abs()
}

/// The drag kernel of both solvers: the force on a particle is
/// F = (1/2) rho_f (pi d^2 / 4) f(phi, Re_p) C_D(Re*) |u_r| u_r (Chassagne et al. 2023
/// eqs 2.9-2.11, Maurin et al. 2015 eqs 11-12) with Re* the Reynolds number of the
/// hindrance's declared convention ([`Hindrance::reynolds_convention`]). Written with
/// C_D Re, finite as Re -> 0: C_D(Re*) Re = cd_re(Re*) Re / Re* = cd_re(Re*) / c(phi),
/// c = Re* / Re_p the convention's ratio.
#[derive(Clone, Copy, Debug)]
pub struct DragKernel<'a> {
    /// single-particle drag
    pub drag: &'a dyn DragLaw,
    /// hindrance
    pub hindrance: &'a dyn Hindrance,
    convention: DragReynolds,
}

/// Per-point values of a [`DragKernel`] evaluation, structure of arrays.
#[derive(Clone, Debug, Default)]
pub struct DragPoints {
    /// Re* of the hindrance's convention
    pub re_star: Vec<f64>,
    /// C_D(Re*) Re*
    pub cd_re: Vec<f64>,
    /// hindrance factor f(phi, Re_p)
    pub factor: Vec<f64>,
}

impl DragPoints {
    /// Storage for `n` points.
    pub fn new(n: usize) -> Self {
        Self { re_star: vec![0.0; n], cd_re: vec![0.0; n], factor: vec![0.0; n] }
    }
}

impl<'a> DragKernel<'a> {
    /// The kernel of `drag` and `hindrance`, with the hindrance's declared convention.
    pub fn new(drag: &'a dyn DragLaw, hindrance: &'a dyn Hindrance) -> Self {
        Self { drag, hindrance, convention: hindrance.reynolds_convention() }
    }

    /// The hindrance's Reynolds-number convention.
    pub fn convention(&self) -> DragReynolds {
        self.convention
    }

    /// Re* / Re_p at volume fraction `phi`.
    #[inline]
    pub fn reynolds_ratio(&self, phi: f64) -> f64 {
        self.convention.ratio(phi)
    }

    /// Evaluate the kernel at the points (phi, Re_p): one batch call of each closure.
    pub fn evaluate(&self, phi: &[f64], re_p: &[f64], out: &mut DragPoints) {
        for ((s, &p), &r) in out.re_star.iter_mut().zip(phi).zip(re_p) {
            *s = self.convention.ratio(p) * r;
        }
        self.drag.cd_re_batch(&out.re_star, &mut out.cd_re);
        self.hindrance.factor_batch(phi, re_p, &mut out.factor);
    }

    /// [`DragKernel::evaluate`] at the same volume fractions as `base` and other Reynolds
    /// numbers (a difference in Re): the hindrance factor of `base` is reused when the
    /// hindrance does not depend on Re, the same values without its batch call.
    pub fn evaluate_at_reynolds(&self, base: &DragPoints, phi: &[f64], re_p: &[f64], out: &mut DragPoints) {
        if self.hindrance.depends_on_reynolds() {
            return self.evaluate(phi, re_p, out);
        }
        for ((s, &p), &r) in out.re_star.iter_mut().zip(phi).zip(re_p) {
            *s = self.convention.ratio(p) * r;
        }
        self.drag.cd_re_batch(&out.re_star, &mut out.cd_re);
        out.factor.copy_from_slice(&base.factor);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flow_scales_above_the_bed() {
        let zc = [0.5, 1.5, 2.5, 3.5];
        let dz = [1.0; 4];
        let phi = [0.6, 0.5, 0.01, 0.0];
        let bed = bed_surface(&zc, &phi, 0.0);
        assert_eq!(bed, 1.5);
        let s = flow_scales(&zc, &dz, &[0.0, 0.1, 1.0, 2.0], 4.0, bed);
        assert_eq!(s.depth, 2.5);
        assert_eq!(s.bulk_velocity, 1.5);
        assert_eq!(bed_surface(&zc, &[0.0; 4], 0.25), 0.25);
    }

    /// The peer script's bed: the highest peak above the threshold, read from the top.
    /// A layered quasi-2D bed (peaks 0.7 and 0.65 at cells 2 and 5, a loose top layer
    /// peaking at 0.45 in cell 8): with 0.5 the bed is the lower face of cell 6, the first
    /// cell from the top above 0.5 on the upper flank of a peak; with 0.4 the loose layer's
    /// flank (cell 9); above every value, or on a profile without a peak (phi rising to the
    /// top), the column bottom.
    #[test]
    fn peak_bed_elevation_is_the_top_of_the_highest_dense_peak() {
        let phi = [0.3, 0.6, 0.7, 0.55, 0.5, 0.65, 0.52, 0.2, 0.45, 0.41, 0.0, 0.0];
        assert_eq!(peak_bed_elevation(&phi, 0.5, 0.5), 3.0);
        assert_eq!(peak_bed_elevation(&phi, 0.5, 0.4), 4.5);
        assert_eq!(peak_bed_elevation(&phi, 0.5, 0.75), 0.0);
        assert_eq!(peak_bed_elevation(&[0.1, 0.2, 0.6, 0.7], 1.0, 0.5), 0.0);
        assert_eq!(peak_bed_elevation(&[], 1.0, 0.5), 0.0);
    }

    /// The kernel evaluates C_D at the hindrance's declared Re*: Dallavalle C_D = 0.4 +
    /// 24.4 / Re* (Maurin et al. 2015 eq 12) with Di Felice's superficial Re* = (1 - phi) Re_p
    /// and Richardson-Zaki's interstitial one; C_D Re_p = cd_re(Re*) / c(phi) stays finite
    /// (24.4 / c) as Re_p -> 0.
    #[test]
    fn the_kernel_uses_the_declared_convention() {
        use saltus_closures::drag::Dallavalle;
        use saltus_closures::hindrance::{DiFelice, RichardsonZaki};
        let drag = Dallavalle::default();
        let phi = [0.0, 0.3, 0.5, 0.3];
        let re = [10.0, 10.0, 100.0, 0.0];
        let mut pts = DragPoints::new(4);
        let sup = DiFelice::default();
        let k = DragKernel::new(&drag, &sup);
        assert_eq!(k.convention(), DragReynolds::Superficial);
        k.evaluate(&phi, &re, &mut pts);
        for i in 0..4 {
            let re_star = (1.0 - phi[i]) * re[i];
            assert_eq!(pts.re_star[i], re_star);
            assert!((pts.cd_re[i] - (0.4 * re_star + 24.4)).abs() < 1e-12);
            assert_eq!(pts.factor[i], sup.factor(phi[i], re[i]));
        }
        // C_D(Re*) Re_p at Re_p -> 0: 24.4 / (1 - phi)
        assert!((pts.cd_re[3] / k.reynolds_ratio(phi[3]) - 24.4 / 0.7).abs() < 1e-12);
        let rz = RichardsonZaki::default();
        let k = DragKernel::new(&drag, &rz);
        assert_eq!(k.convention(), DragReynolds::Interstitial);
        k.evaluate(&phi, &re, &mut pts);
        assert_eq!(pts.re_star, re);
        assert_eq!(pts.factor[2], 0.5f64.powf(-3.1));
    }
}
