//! The half-cylinders of the Frey bottom (`solver.lagrangian.bottom = "half_cylinders"`).
//!
//! Maurin et al. 2015 section III A: "the channel bottom is made of metal half-cylinders
//! of diameter d, fixed at a random elevation between -2.75 mm and 2.75 mm with steps of
//! 0.5 mm to break clusterization". Here: `n = floor(L_x / d)` cylinders of radius
//! R = d/2, axes along y (across the channel, over its whole width), axis k at
//! x = (k + 1/2) L_x / n and z = d + (j_k - 5.5) d / 12 with j_k drawn uniformly in
//! 0..12 ([`saltus_core::scene::FREY_LEVELS`]) from the scene seed. Only the upper half of
//! a cylinder can be reached (a bead is wider than the gap between two of them), so
//! whole cylinders stand for the half ones.
//!
//! A sphere of radius r touches cylinder k when the distance from its centre to the axis
//! (in the x-z plane, x periodic) is below r + R: the contact is the one with the nearest
//! point of the axis, normal in the x-z plane, overlap r + R - distance, and the same law
//! as a bead against a fixed bead of radius R (effective mass the bead's, effective
//! radius r R / (r + R), the tangential spring kept per cylinder while the contact
//! lasts). A sphere no wider than the spacing touches at most the two cylinders it sits
//! between; [`MAX_TOUCHES`] slots leave room for a grain of the largest dispersion.

use serde::{Deserialize, Serialize};

use super::contact::{contact_force, cross, ContactInput, ContactLaw};

/// Most cylinders one sphere can touch at once (its diameter is at most the spacing
/// times 1.09, so it reaches at most the three nearest axes).
pub const MAX_TOUCHES: usize = 3;

/// The tangential springs of one sphere's cylinder contacts: (cylinder index + 1, spring
/// in m); index 0 is a free slot.
pub type Touches = [(u32, [f64; 3]); MAX_TOUCHES];

/// One cylinder contact as the integration records it for the granular fields: the
/// branch from the sphere's centre to the cylinder's surface, the force on the sphere
/// and the dissipated power.
pub type CylinderTouch = ([f64; 3], [f64; 3], f64);

/// Fixed cylinders of radius `radius`, axes along y at x = (k + 1/2) `spacing`, z = `z[k]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HalfCylinders {
    /// radius R (m)
    pub radius: f64,
    /// axis spacing along x (m); the spacing times the count is the period L_x
    pub spacing: f64,
    /// axis heights (m)
    pub z: Vec<f64>,
}

/// The state of the sphere the contacts act on.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    /// centre (m)
    pub x: [f64; 3],
    /// velocity (m/s)
    pub v: [f64; 3],
    /// angular velocity (rad/s)
    pub w: [f64; 3],
    /// radius (m)
    pub r: f64,
    /// sqrt of the mass (sqrt kg)
    pub sqrt_m: f64,
}

impl HalfCylinders {
    /// The period along x (m).
    pub fn period(&self) -> f64 {
        self.spacing * self.z.len() as f64
    }

    /// Add the force and torque of the cylinders on sphere `s` to `ft` (contact by
    /// contact, in axis order), with the tangential springs in `hist` updated (a spring
    /// is forgotten when its contact ends); `each` sees every contact with its history
    /// slot (for the granular fields).
    #[inline]
    pub fn add_forces(
        &self,
        s: &Sphere,
        law: &ContactLaw,
        dt: f64,
        hist: &mut Touches,
        ft: (&mut [f64; 3], &mut [f64; 3]),
        mut each: impl FnMut(usize, CylinderTouch),
    ) {
        let (f, t) = ft;
        let n_cyl = self.z.len();
        if n_cyl == 0 {
            return;
        }
        let period = self.period();
        let reach = s.r + self.radius;
        let xs = s.x[0].rem_euclid(period);
        // the axes within reach along x: k from ceil((x - reach)/s - 1/2) to
        // floor((x + reach)/s - 1/2), at most MAX_TOUCHES of them
        let lo = ((xs - reach) / self.spacing - 0.5).ceil() as i64;
        let hi = ((xs + reach) / self.spacing - 0.5).floor() as i64;
        // the cylinders in contact: (index, branch to the axis, distance)
        let mut hits = [(0usize, [0.0; 3], 0.0); MAX_TOUCHES];
        let mut count = 0;
        for kk in lo..=hi.min(lo + MAX_TOUCHES as i64 - 1) {
            let k = kk.rem_euclid(n_cyl as i64) as usize;
            let d = [(kk as f64 + 0.5) * self.spacing - xs, 0.0, self.z[k] - s.x[2]];
            let r2 = d[0] * d[0] + d[2] * d[2];
            if r2 < reach * reach {
                hits[count] = (k, d, r2.sqrt());
                count += 1;
            }
        }
        let hits = &hits[..count];
        // forget the springs of contacts that ended, before new ones take their slots
        for h in hist.iter_mut() {
            if h.0 != 0 && !hits.iter().any(|c| c.0 as u32 + 1 == h.0) {
                *h = (0, [0.0; 3]);
            }
        }
        for &(k, d, dist) in hits {
            let id = k as u32 + 1;
            let slot = match hist.iter().position(|h| h.0 == id) {
                Some(q) => q,
                None => {
                    // a free slot exists: at most MAX_TOUCHES contacts hold slots
                    let q = hist.iter().position(|h| h.0 == 0).unwrap_or(0);
                    hist[q] = (id, [0.0; 3]);
                    q
                }
            };
            let n = [d[0] / dist, 0.0, d[2] / dist];
            let spin = cross([s.r * s.w[0], s.r * s.w[1], s.r * s.w[2]], n);
            let v_rel = [-s.v[0] - spin[0], -s.v[1] - spin[1], -s.v[2] - spin[2]];
            let spin_n = 0.5 * (s.w[0] * n[0] + s.w[1] * n[1] + s.w[2] * n[2]);
            let c = ContactInput {
                n,
                delta: reach - dist,
                v_rel,
                sqrt_m: s.sqrt_m,
                r_eff: s.r * self.radius / reach,
                spin_n,
            };
            let (fc, power) = contact_force(law, &c, &mut hist[slot].1, dt);
            let tc = cross(n, fc);
            for c in 0..3 {
                f[c] += fc[c];
                t[c] += s.r * tc[c];
            }
            let gap = dist - self.radius;
            each(slot, ([n[0] * gap, 0.0, n[2] * gap], fc, power));
        }
    }

    /// Elastic energy of the normal springs of the linear law between the cylinders and
    /// sphere (centre `x`, radius `r`) (J).
    pub fn normal_spring_energy(&self, x: [f64; 3], r: f64, kn: f64) -> f64 {
        let mut e = 0.0;
        self.each_overlap(x, r, |delta| e += 0.5 * kn * delta * delta);
        e
    }

    /// Call `f(delta)` for every half-cylinder that the sphere of centre `x` and radius
    /// `r` overlaps, delta > 0 the overlap (m).
    pub fn each_overlap(&self, x: [f64; 3], r: f64, mut f: impl FnMut(f64)) {
        let period = self.period();
        let xs = x[0].rem_euclid(period);
        let reach = r + self.radius;
        for (k, &z) in self.z.iter().enumerate() {
            let dx = ((k as f64 + 0.5) * self.spacing - xs + 0.5 * period).rem_euclid(period) - 0.5 * period;
            let delta = reach - (dx * dx + (z - x[2]) * (z - x[2])).sqrt();
            if delta > 0.0 {
                f(delta);
            }
        }
    }
}
