//! The contact sums of a sampled DEM step: each contact's stress, heat flux, dissipated
//! power and count, divided between the averaging slices its branch vector crosses (the
//! definitions are in [`crate::lagrangian::stats::granular`]).
//!
//! The contact sums are taken in the contact loop of the sampled DEM steps only: the
//! pair loop of such a step runs over fixed groups of [`GROUP`] pairs, each with its own
//! slab of slice sums, added in group order afterwards; the wall contacts are recorded per
//! particle and added in particle order. No step allocates once the buffers reached their
//! size, and the sums do not depend on the number of threads.

use saltus_core::grain::ball_volume;
use serde::{Deserialize, Serialize};

use super::chunks::CHUNK;
use super::walls::RECORD_SLOTS;

/// Contact sums per slice, in this order: P_xx, P_yy, P_zz, P_xz, P_yz (times V), raw
/// heat flux, dissipated power, contacts.
pub const CONTACT_FIELDS: usize = 8;
pub(crate) const PXX: usize = 0;
pub(crate) const PYY: usize = 1;
pub(crate) const PZZ: usize = 2;
pub(crate) const PXZ: usize = 3;
pub(crate) const PYZ: usize = 4;
pub(crate) const HEAT: usize = 5;
pub(crate) const DISS: usize = 6;
pub(crate) const COUNT: usize = 7;

/// Pairs per work item of a sampled step: each item owns one slab of slice sums, so the
/// slabs, and the order they are added in, are the same whatever the number of threads.
pub const GROUP: usize = 4 * CHUNK;

/// A wall contact of one particle as recorded by the integration: the centre height and
/// radius of the particle, the height where its branch meets the wall, then the
/// [`CONTACT_FIELDS`] values (all zero without contact).
pub type WallRecord = [f64; CONTACT_FIELDS + 3];

/// The averaging slices in particle coordinates: `n` slices of height `dz` from `base`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Slices {
    /// height of the bottom of the first slice (m)
    pub base: f64,
    /// slice height (m)
    pub dz: f64,
    /// number of slices
    pub n: usize,
}

/// One end of a branch vector: a grain of centre height `z` and radius `r`, or a point
/// (`r` = 0: where a branch meets a wall).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct End {
    /// height (m)
    pub z: f64,
    /// radius (m), 0 for a point
    pub r: f64,
}

impl End {
    /// int_{-inf}^h (fraction of the end below z') dz' (m): for a grain, the integral of
    /// its cap volume (pi s^2 (3r - s) / 3, s = h - (z - r)) over its volume,
    /// (pi (r s^3 - s^4 / 4) / 3 + V (h - z - r)^+) / V; for a point, (h - z)^+.
    #[inline(always)]
    fn below(&self, h: f64) -> f64 {
        if self.r <= 0.0 {
            return (h - self.z).max(0.0);
        }
        let r = self.r;
        let s = (h - (self.z - r)).clamp(0.0, 2.0 * r);
        let s3 = s * s * s;
        (r * s3 - 0.25 * s3 * s) / (4.0 * r * r * r) + (h - self.z - r).max(0.0)
    }

    /// Fraction of the end between heights `h0` and `h1`.
    #[inline(always)]
    fn share(&self, h0: f64, h1: f64) -> f64 {
        if self.r <= 0.0 {
            return if self.z >= h0 && self.z < h1 { 1.0 } else { 0.0 };
        }
        let v = ball_volume(self.r);
        (super::slicing::cap_volume(self.z, self.r, h1) - super::slicing::cap_volume(self.z, self.r, h0)) / v
    }
}

impl Slices {
    /// Call `f(c, w, u)` for every slice c the contact of ends `a` and `b` reaches, `w`
    /// and `u` being the two shares of the contact in it:
    ///
    /// ```text
    /// w_c = int_{slice c} [S_a(z) - S_b(z)] dz / (z_b - z_a)
    /// u_c = int_{slice c} |S_a(z) - S_b(z)| dz / int |S_a(z) - S_b(z)| dz
    /// ```
    ///
    /// with S the fraction of an end below z: the branch from a to b, each end smeared
    /// over its grain like phi is (Maurin eq A1). `w` is the share of the values that
    /// carry the branch's rise z_b - z_a (P_zz, P_xz, P_yz, the heat flux): with it the
    /// contact stress's divergence is exactly the contact forces weighted as phi weights
    /// them (module documentation of the granular fields), the rise cancelling the
    /// division. `u` is the share of the others (P_xx, P_yy, the dissipation, the count),
    /// which must not change sign: S_a - S_b does when one end reaches both above and
    /// below the other (grains of different sizes on a branch steeper than the difference
    /// of their radii, or a grain overlapping a wall point), and `w` then takes negative
    /// values and, for a branch almost level, values far above 1. Both add up to 1 over
    /// the slices (parts outside the slices are dropped), and they are equal where S_a -
    /// S_b keeps its sign (any two grains of one size). A horizontal branch (|z_b - z_a|
    /// below 1e-9 of the radii) takes the limit, the mean of the two ends' volume shares,
    /// for both.
    #[inline]
    pub fn branch(&self, a: End, b: End, mut f: impl FnMut(usize, f64, f64)) {
        let (dz, base) = (self.dz, self.base);
        if !(a.z.is_finite() && b.z.is_finite()) {
            return;
        }
        let lo = (a.z - a.r).min(b.z - b.r) - base;
        let hi = (a.z + a.r).max(b.z + b.r) - base;
        // compared so that NaN falls out too
        if !(hi >= 0.0 && lo < self.n as f64 * dz) {
            return;
        }
        let first = ((lo / dz).floor().max(0.0)) as usize;
        let last = ((hi / dz).floor() as usize).min(self.n - 1);
        let rise = b.z - a.z;
        let face = |c: usize| base + c as f64 * dz;
        if rise.abs() <= 1e-9 * (a.r + b.r) {
            for c in first..=last {
                let (h0, h1) = (face(c), face(c + 1));
                let w = 0.5 * (a.share(h0, h1) + b.share(h0, h1));
                f(c, w, w);
            }
            return;
        }
        let gap = |h: f64| a.below(h) - b.below(h);
        let mut below = gap(face(first));
        let Some((cross, at, total)) = sign_change(a, b, rise).map(|(z, t)| (z, gap(z), t)) else {
            for c in first..=last {
                let upto = gap(face(c + 1));
                let w = (upto - below) / rise;
                f(c, w, w);
                below = upto;
            }
            return;
        };
        for c in first..=last {
            let (h0, h1) = (face(c), face(c + 1));
            let upto = gap(h1);
            let w = (upto - below) / rise;
            let u = if cross > h0 && cross < h1 {
                ((at - below).abs() + (upto - at).abs()) / total
            } else {
                (upto - below).abs() / total
            };
            f(c, w, u);
            below = upto;
        }
    }
}

/// Where S_a - S_b changes sign on a branch of rise `rise` (not level), with the integral
/// of |S_a - S_b| over z; `None` when it keeps its sign. Each S is the fraction of a
/// ball-shaped (or point) distribution below z, F((z - z_e) / r_e) with one F: S_a - S_b
/// changes sign where (z - z_a) / r_a = (z - z_b) / r_b inside both ends, which happens
/// iff one end reaches past the other on both sides, |r_a - r_b| > |z_b - z_a|. The
/// integral of S_a - S_b over all z is the rise, so the integral of its absolute value is
/// |G(z*)| + |rise - G(z*)| with G(h) its integral below h.
#[inline]
fn sign_change(a: End, b: End, rise: f64) -> Option<(f64, f64)> {
    if (a.r - b.r).abs() <= rise.abs() {
        return None;
    }
    let z = (a.z * b.r - b.z * a.r) / (b.r - a.r);
    let z = z.clamp((a.z - a.r).max(b.z - b.r), (a.z + a.r).min(b.z + b.r));
    let g = a.below(z) - b.below(z);
    let total = g.abs() + (rise - g).abs();
    (total > 0.0 && total.is_finite()).then_some((z, total))
}

/// Which of the [`CONTACT_FIELDS`] carry the branch's rise, and so take the share `w` of
/// [`Slices::branch`]; the others take `u`.
const CARRIES_RISE: [bool; CONTACT_FIELDS] = {
    let mut r = [false; CONTACT_FIELDS];
    r[PZZ] = true;
    r[PXZ] = true;
    r[PYZ] = true;
    r[HEAT] = true;
    r
};

/// The values one contact adds to its slices: `b` the branch vector from particle a to
/// its partner, `f` the force on a, `va`/`vb` the translational velocities, `power` the
/// dissipated power (W), `count` 1 for a pair, 1/2 for a wall (one particle's contact).
#[inline(always)]
pub fn contact_values(
    b: [f64; 3],
    f: [f64; 3],
    va: [f64; 3],
    vb: [f64; 3],
    power: f64,
    count: f64,
) -> [f64; CONTACT_FIELDS] {
    let work = 0.5 * (f[0] * (va[0] + vb[0]) + f[1] * (va[1] + vb[1]) + f[2] * (va[2] + vb[2]));
    [-f[0] * b[0], -f[1] * b[1], -f[2] * b[2], -f[0] * b[2], -f[1] * b[2], -b[2] * work, power, count]
}

/// Add `values` of the contact of ends `a` and `b` into `slab` (slice-major,
/// [`CONTACT_FIELDS`] per slice), divided as [`Slices::branch`] divides it: the fields
/// that carry the branch's rise by `w`, the others by `u`.
#[inline(always)]
pub fn spread(slices: &Slices, slab: &mut [f64], a: End, b: End, values: &[f64; CONTACT_FIELDS]) {
    slices.branch(a, b, |c, w, u| {
        let row = &mut slab[c * CONTACT_FIELDS..(c + 1) * CONTACT_FIELDS];
        for ((r, v), &rise) in row.iter_mut().zip(values).zip(&CARRIES_RISE) {
            *r += (if rise { w } else { u }) * v;
        }
    });
}

/// The contact sums of one sampled DEM step (scratch of the DEM, refilled by every
/// sampled step).
#[derive(Clone, Debug, Default)]
pub struct ContactSums {
    /// the slices of this step
    pub slices: Slices,
    /// one slab of `slices.n` x [`CONTACT_FIELDS`] per group of [`GROUP`] pairs
    pub slabs: Vec<f64>,
    /// the wall (and half-cylinder) contacts of each mobile particle
    pub walls: Vec<[WallRecord; RECORD_SLOTS]>,
}

impl ContactSums {
    /// Zeroed sums for `pairs` pairs and `mobile` particles on `slices`.
    pub fn prepare(&mut self, slices: Slices, pairs: usize, mobile: usize) {
        self.slices = slices;
        self.slabs.clear();
        self.slabs.resize(pairs.div_ceil(GROUP).max(1) * slices.n * CONTACT_FIELDS, 0.0);
        self.walls.clear();
        self.walls.resize(mobile, [[0.0; CONTACT_FIELDS + 3]; RECORD_SLOTS]);
    }

    /// Length of one slab.
    pub fn slab_len(&self) -> usize {
        self.slices.n * CONTACT_FIELDS
    }

    /// Add the slabs in group order, then the wall contacts in particle order, into
    /// `out` (slice-major, [`CONTACT_FIELDS`] per slice).
    pub fn add_to(&self, out: &mut [f64]) {
        for slab in self.slabs.chunks_exact(self.slab_len().max(1)) {
            out.iter_mut().zip(slab).for_each(|(o, s)| *o += s);
        }
        for rec in self.walls.iter().flatten() {
            if rec[3 + COUNT] > 0.0 {
                let values: &[f64; CONTACT_FIELDS] = rec[3..].try_into().unwrap_or(&[0.0; CONTACT_FIELDS]);
                spread(&self.slices, out, End { z: rec[0], r: rec[1] }, End { z: rec[2], r: 0.0 }, values);
            }
        }
    }
}
