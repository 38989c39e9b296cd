//! The pair loop of the linear contact law in three passes, so that the contact force
//! itself runs as one vector loop:
//!
//! 1. over the listed pairs of a block, without a branch: the branch vector and the
//!    overlap test, the pairs in contact compacted into a list, the histories and the
//!    force slots of the others cleared;
//! 2. the inputs of the pairs in contact gathered into structure-of-arrays lanes
//!    ([`Lanes`]);
//! 3. the force of every contact in one loop without a branch ([`linear_lanes`]), then
//!    the results scattered to the pairs' slots.
//!
//! The force loop does, operation by operation and in the same order, what
//! [`contact_force`](super::contact::contact_force) does for the linear law (the Coulomb
//! cap as a selected factor, x * 1 = x; the slip power as a selected term, x + 0 = x), so
//! the forces, histories and powers are bit for bit those of the pair-by-pair loop. The
//! loop is compiled twice, for the baseline x86-64 (SSE2) and for AVX2 + FMA, and the
//! version the processor supports is picked at the first call (runtime dispatch,
//! `multiversion`); it uses no fused multiply-add and no reassociation, and square root
//! and division are correctly rounded in both, so both versions give the same bits and a
//! run does not depend on the processor that runs it.
//!
//! Passes 1 and 2 read the particles at random, by the pairs' indices, from the arrays
//! of [`super::particles::Particles`]: records packed once per step (position and radius
//! in half a cache line, velocity and spin in one) were tried and gave no measurable
//! gain, so the loop reads the arrays themselves.

use std::cell::RefCell;

use multiversion::multiversion;

use super::chunks::CHUNK;
use super::contact::{contact_force, cross, ContactInput, ContactLaw};
use super::neighbours::NeighbourList;

/// A pair in contact: the branch vector from i to j, the unit normal, the force on i (N)
/// and the power the contact dissipates (W).
type Touch = ([f64; 3], [f64; 3], [f64; 3], f64);

/// What the force of one listed pair reads, as slices: borrowed once per step, so that
/// the pair loop, inlined, keeps their addresses in registers instead of reloading them
/// through the particle and list structures for every pair.
pub(crate) struct PairView<'a> {
    pub(crate) x: [&'a [f64]; 3],
    pub(crate) v: [&'a [f64]; 3],
    pub(crate) w: [&'a [f64]; 3],
    pub(crate) radius: &'a [f64],
    pub(crate) i: &'a [u32],
    pub(crate) j: &'a [u32],
    pub(crate) shift: &'a [[f64; 3]],
    pub(crate) sqrt_m: &'a [f64],
    pub(crate) r_eff: &'a [f64],
    pub(crate) law: &'a ContactLaw,
    pub(crate) dt: f64,
}

impl PairView<'_> {
    /// The force of pair q with history h: the branch vector, the unit normal, the force
    /// on i and the dissipated power, or None out of contact.
    #[inline(always)]
    fn force(&self, q: usize, h: &mut [f64; 3]) -> Option<Touch> {
        let (a, b) = (self.i[q] as usize, self.j[q] as usize);
        let s = self.shift[q];
        let [x, y, z] = self.x;
        let d = [x[b] + s[0] - x[a], y[b] + s[1] - y[a], z[b] + s[2] - z[a]];
        let (ra, rb) = (self.radius[a], self.radius[b]);
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let reach = ra + rb;
        if r2 >= reach * reach {
            return None;
        }
        let dist = r2.sqrt();
        let n = [d[0] / dist, d[1] / dist, d[2] / dist];
        let [wx, wy, wz] = self.w;
        let [vx, vy, vz] = self.v;
        let arm = [ra * wx[a] + rb * wx[b], ra * wy[a] + rb * wy[b], ra * wz[a] + rb * wz[b]];
        let spin = cross(arm, n);
        let v_rel = [vx[b] - vx[a] - spin[0], vy[b] - vy[a] - spin[1], vz[b] - vz[a] - spin[2]];
        // the rotated spring's twist; the branch is the same for every pair of a run
        let spin_n = if self.law.rotate_history {
            0.5 * ((wx[a] + wx[b]) * n[0] + (wy[a] + wy[b]) * n[1] + (wz[a] + wz[b]) * n[2])
        } else {
            0.0
        };
        let c = ContactInput { n, delta: reach - dist, v_rel, sqrt_m: self.sqrt_m[q], r_eff: self.r_eff[q], spin_n };
        let (f, power) = contact_force(self.law, &c, h, self.dt);
        Some((d, n, f, power))
    }

    /// The force of pair q into its slots (zero out of contact, the history cleared);
    /// the branch vector, the force and the power in contact.
    #[inline(always)]
    pub(crate) fn write(
        &self,
        q: usize,
        h: &mut [f64; 3],
        f_out: &mut [f64; 3],
        t_out: &mut [f64; 3],
    ) -> Option<TouchSums> {
        match self.force(q, h) {
            Some((d, n, f, power)) => {
                *f_out = f;
                *t_out = cross(n, f);
                Some((d, f, power))
            }
            None => {
                *h = [0.0; 3];
                *f_out = [0.0; 3];
                *t_out = [0.0; 3];
                None
            }
        }
    }
}

/// The branch vector, force on i and dissipated power of a pair in contact.
type TouchSums = ([f64; 3], [f64; 3], f64);

// the compaction indexes its lanes with a mask of CHUNK - 1
const _: () = assert!(CHUNK.is_power_of_two());

/// The contacts of a block of at most [`CHUNK`] pairs as a structure of arrays; one per
/// thread, reused from block to block.
pub(crate) struct Lanes {
    /// index of the contact's pair in the block
    k: [u32; CHUNK],
    /// whether pair k of the block is in contact
    now: [bool; CHUNK],
    /// branch vector x_j - x_i
    d: [[f64; CHUNK]; 3],
    /// R_i + R_j
    reach: [f64; CHUNK],
    /// R_i w_i + R_j w_j
    arm: [[f64; CHUNK]; 3],
    /// v_j - v_i
    dv: [[f64; CHUNK]; 3],
    /// sqrt of the effective mass
    sqrt_m: [f64; CHUNK],
    /// tangential history, in and out
    h: [[f64; CHUNK]; 3],
    /// force on i
    f: [[f64; CHUNK]; 3],
    /// torque direction n x f
    t: [[f64; CHUNK]; 3],
    /// dissipated power
    power: [f64; CHUNK],
}

impl Lanes {
    fn new() -> Box<Self> {
        let z = [[0.0; CHUNK]; 3];
        Box::new(Self {
            k: [0; CHUNK],
            now: [false; CHUNK],
            d: z,
            reach: [0.0; CHUNK],
            arm: z,
            dv: z,
            sqrt_m: [0.0; CHUNK],
            h: z,
            f: z,
            t: z,
            power: [0.0; CHUNK],
        })
    }
}

thread_local! {
    /// this thread's lanes: allocated at its first block, then reused
    static LANES: RefCell<Box<Lanes>> = RefCell::new(Lanes::new());
}

/// One contact of a block, for the callers that take the granular sums: the pair, the
/// branch vector, the force on i and the dissipated power.
pub(crate) type Contact = (usize, [f64; 3], [f64; 3], f64);

/// Which pairs of the list were in contact at the last step: a pair out of contact holds
/// a zero history and zero force slots, so that only the pairs that leave contact need
/// clearing. Scratch, laid out again (every pair flagged, i.e. cleared at the next step
/// if out of contact) for each new list, after a restart and after a clone.
#[derive(Debug, Default)]
pub(crate) struct Touching {
    /// pair q was in contact at the last step
    was: Vec<bool>,
    /// the build of the list the flags belong to (0: none)
    build: usize,
}

impl Clone for Touching {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl Touching {
    /// The flags of `list`, laid out anew unless they already belong to it.
    pub(crate) fn prepare(&mut self, list: &NeighbourList) -> &mut [bool] {
        if self.build != list.builds || self.was.len() != list.len() {
            self.build = list.builds;
            self.was.clear();
            self.was.resize(list.len(), true);
        }
        &mut self.was
    }
}

/// What the pair loop writes for a run of pairs: their histories, force slots (force on
/// i), torque slots (n x f) and contact flags.
pub(crate) struct PairOut<'a> {
    pub(crate) hist: &'a mut [[f64; 3]],
    pub(crate) f: &'a mut [[f64; 3]],
    pub(crate) t: &'a mut [[f64; 3]],
    pub(crate) was: &'a mut [bool],
}

impl PairView<'_> {
    /// The linear-law forces of the pairs `o..o + out.hist.len()` into their slots, zero
    /// out of contact with the history cleared; `out.was` flags the pairs in contact at
    /// the last step (updated; the others hold zeros already), and `each` sees every pair
    /// in contact, in pair order. Bit for bit the numbers of [`PairView::write`] pair by
    /// pair.
    pub(crate) fn linear_pairs(&self, o: usize, out: PairOut<'_>, mut each: impl FnMut(Contact)) {
        let PairOut { hist, f, t, was } = out;
        LANES.with(|lanes| {
            let l = &mut lanes.borrow_mut();
            let blocks = hist.chunks_mut(CHUNK).zip(f.chunks_mut(CHUNK)).zip(t.chunks_mut(CHUNK));
            for (b, (((hist, f), t), was)) in blocks.zip(was.chunks_mut(CHUNK)).enumerate() {
                self.linear_block(o + b * CHUNK, PairOut { hist, f, t, was }, l, &mut each);
            }
        });
    }

    #[inline(always)]
    fn linear_block(&self, o: usize, out: PairOut<'_>, l: &mut Lanes, each: &mut impl FnMut(Contact)) {
        let PairOut { hist, f: f_out, t: t_out, was } = out;
        let n = hist.len().min(CHUNK).min(f_out.len()).min(t_out.len()).min(was.len());
        let [x, y, z] = self.x;
        let (pi, pj, shift) = (&self.i[o..o + n], &self.j[o..o + n], &self.shift[o..o + n]);
        let mut m = 0;
        for (k, (((&a, &b), s), now)) in pi.iter().zip(pj).zip(shift).zip(&mut l.now[..n]).enumerate() {
            let (a, b) = (a as usize, b as usize);
            let d = [x[b] + s[0] - x[a], y[b] + s[1] - y[a], z[b] + s[2] - z[a]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let reach = self.radius[a] + self.radius[b];
            let touch = r2 < reach * reach;
            *now = touch;
            // written for every pair, kept (m advanced) for the pairs in contact only;
            // m <= k < CHUNK, so the mask only tells the compiler there is no bound to
            // check. Only the index: keeping the branch vector and the particles too (8
            // stores per pair instead of 2) moved the time of pass 2 into this loop.
            l.k[m & (CHUNK - 1)] = k as u32;
            m += touch as usize;
        }
        // the pairs that left contact (about one in five contacts per step at the peer's
        // time step): one branch on both flags, in its own loop (folded into the loop
        // above, the compiler branched on the overlap test, wrong for one pair in three)
        let ends = hist[..n].iter_mut().zip(&mut f_out[..n]).zip(&mut t_out[..n]);
        for ((w, &now), ((h, f), t)) in was[..n].iter_mut().zip(&l.now[..n]).zip(ends) {
            if (*w as u8) > (now as u8) {
                *h = [0.0; 3];
                *f = [0.0; 3];
                *t = [0.0; 3];
            }
            *w = now;
        }
        let [wx, wy, wz] = self.w;
        let [vx, vy, vz] = self.v;
        for c in 0..m.min(CHUNK) {
            let k = l.k[c] as usize;
            let q = o + k;
            let (a, b) = (self.i[q] as usize, self.j[q] as usize);
            let s = self.shift[q];
            l.d[0][c] = x[b] + s[0] - x[a];
            l.d[1][c] = y[b] + s[1] - y[a];
            l.d[2][c] = z[b] + s[2] - z[a];
            let (ra, rb) = (self.radius[a], self.radius[b]);
            l.reach[c] = ra + rb;
            l.arm[0][c] = ra * wx[a] + rb * wx[b];
            l.arm[1][c] = ra * wy[a] + rb * wy[b];
            l.arm[2][c] = ra * wz[a] + rb * wz[b];
            l.dv[0][c] = vx[b] - vx[a];
            l.dv[1][c] = vy[b] - vy[a];
            l.dv[2][c] = vz[b] - vz[a];
            l.sqrt_m[c] = self.sqrt_m[q];
            for (lane, &h) in l.h.iter_mut().zip(&hist[k]) {
                lane[c] = h;
            }
        }
        let law = LinearLaw {
            kn: self.law.kn,
            kt: self.law.kt,
            mu: self.law.friction,
            damping_factor: self.law.damping_factor(),
            dt: self.dt,
            repulsive: self.law.repulsive,
        };
        linear_lanes(&law, m, l);
        for c in 0..m {
            let k = l.k[c] as usize;
            hist[k] = [l.h[0][c], l.h[1][c], l.h[2][c]];
            let f = [l.f[0][c], l.f[1][c], l.f[2][c]];
            f_out[k] = f;
            t_out[k] = [l.t[0][c], l.t[1][c], l.t[2][c]];
            each((o + k, [l.d[0][c], l.d[1][c], l.d[2][c]], f, l.power[c]));
        }
    }
}

/// The constants of the linear law the force loop reads.
struct LinearLaw {
    kn: f64,
    kt: f64,
    mu: f64,
    damping_factor: f64,
    dt: f64,
    repulsive: bool,
}

/// The linear law of [`contact_force`](super::contact::contact_force) (Maurin et al.
/// 2015 section II A: F_n = -(k_n delta - c_n v_n) n, the tangential spring capped by
/// mu |F_n|) on the first `m` contacts of `l`: the unit normal, the relative velocity of
/// the contact point, the force on i, the torque direction n x f, the updated history
/// and the dissipated power, operation by operation in the order of `contact_force`.
/// Compiled for AVX2 + FMA and for the baseline, picked at run time.
#[multiversion(targets("x86_64+avx2+fma"))]
fn linear_lanes(law: &LinearLaw, m: usize, l: &mut Lanes) {
    let m = m.min(CHUNK);
    // every lane cut to the m contacts: no bound check left in the loop
    let [d0, d1, d2] = l.d.each_ref().map(|v| &v[..m]);
    let [a0, a1, a2] = l.arm.each_ref().map(|v| &v[..m]);
    let [v0, v1, v2] = l.dv.each_ref().map(|v| &v[..m]);
    let [h0, h1, h2] = l.h.each_mut().map(|v| &mut v[..m]);
    let [f0, f1, f2] = l.f.each_mut().map(|v| &mut v[..m]);
    let [t0, t1, t2] = l.t.each_mut().map(|v| &mut v[..m]);
    let (reach, sqrt_m, power) = (&l.reach[..m], &l.sqrt_m[..m], &mut l.power[..m]);
    let &LinearLaw { kn, kt, mu, damping_factor, dt, repulsive } = law;
    for c in 0..m {
        let r2 = d0[c] * d0[c] + d1[c] * d1[c] + d2[c] * d2[c];
        let dist = r2.sqrt();
        let n = [d0[c] / dist, d1[c] / dist, d2[c] / dist];
        let spin = cross([a0[c], a1[c], a2[c]], n);
        let v_rel = [v0[c] - spin[0], v1[c] - spin[1], v2[c] - spin[2]];
        let delta = reach[c] - dist;
        let vn = v_rel[0] * n[0] + v_rel[1] * n[1] + v_rel[2] * n[2];
        let damping = damping_factor * sqrt_m[c];
        let fn_ = kn * delta - damping * vn;
        // a repulsive law's pull selected away, with its dashpot work (x + 0 = x below)
        let pulls = repulsive & (fn_ < 0.0);
        let fn_ = if pulls { 0.0 } else { fn_ };
        let vt = [v_rel[0] - vn * n[0], v_rel[1] - vn * n[1], v_rel[2] - vn * n[2]];
        let mut h = [h0[c], h1[c], h2[c]];
        let hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
        for e in 0..3 {
            h[e] += vt[e] * dt - hn * n[e];
        }
        let mut ft = [kt * h[0], kt * h[1], kt * h[2]];
        let ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
        let cap = mu * fn_.max(0.0);
        // ft2 > cap^2 >= 0 implies ft2 > 0 (and kt > 0): the selected quotients are finite
        let slip = ft2 > cap * cap;
        let norm = ft2.sqrt();
        let s = if slip { cap / norm } else { 1.0 };
        for e in 0..3 {
            ft[e] *= s;
            h[e] *= s;
        }
        let slipped = if slip { cap * (norm - cap) / (kt * dt) } else { 0.0 };
        power[c] = if pulls { 0.0 } else { damping * vn * vn } + slipped;
        let f = [-fn_ * n[0] + ft[0], -fn_ * n[1] + ft[1], -fn_ * n[2] + ft[2]];
        let t = cross(n, f);
        (h0[c], h1[c], h2[c]) = (h[0], h[1], h[2]);
        (f0[c], f1[c], f2[c]) = (f[0], f[1], f[2]);
        (t0[c], t1[c], t2[c]) = (t[0], t[1], t[2]);
    }
}

#[cfg(test)]
mod tests {
    use rand::Rng as _;

    use super::*;
    use crate::lagrangian::engine::contact::{ContactLaw, NormalForce};

    #[test]
    fn the_lanes_give_the_forces_of_the_contact_law_bit_for_bit() {
        // pairs of 3 mm grains at 0.8-1.2 times their reach (about half in contact),
        // approaching and receding, spinning, with histories from sticking to sliding
        // (|k_t h| up to twice mu F_n), some that leave contact with a force in their
        // slots: the three passes must give, pair by pair, the force, torque, history
        // and power of the pair-by-pair law (`contact_force`), and clear the rest
        let np = 3 * CHUNK + 17;
        let mut rng = saltus_core::rng::stream(11, 0);
        let mut u = |lo: f64, hi: f64| lo + (hi - lo) * rng.gen::<f64>();
        let (mut x, mut y, mut z, mut radius) = (vec![], vec![], vec![], vec![]);
        let mut vw: [Vec<f64>; 6] = Default::default();
        for _ in 0..np {
            let (ra, rb) = (u(2.7e-3, 3.3e-3), u(2.7e-3, 3.3e-3));
            let (th, ph, dist) = (u(0.0, std::f64::consts::PI), u(0.0, 6.3), u(0.8, 1.2) * (ra + rb));
            let c = [u(0.0, 0.1), u(0.0, 0.1), u(0.0, 0.1)];
            let e = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
            for (k, r) in [(0.0, ra), (dist, rb)] {
                x.push(c[0] + k * e[0]);
                y.push(c[1] + k * e[1]);
                z.push(c[2] + k * e[2]);
                radius.push(r);
                for (m, v) in vw.iter_mut().enumerate() {
                    v.push(if m < 3 { u(-0.5, 0.5) } else { u(-200.0, 200.0) });
                }
            }
        }
        let i: Vec<u32> = (0..np as u32).map(|q| 2 * q).collect();
        let j: Vec<u32> = (0..np as u32).map(|q| 2 * q + 1).collect();
        let shift = vec![[0.0; 3]; np];
        let sqrt_m: Vec<f64> = (0..np).map(|_| u(0.01, 0.015)).collect();
        let r_eff = vec![1.5e-3; np];
        // the repulsive law soft enough that a good part of the contacts pull (the
        // dashpot's c_n v_n above k_n delta) and are clipped
        let repulsive = ContactLaw::linear(10.0, 5.0, 0.7, 0.5).with_normal_force(NormalForce::Repulsive);
        for law in [ContactLaw::linear(3.2e4, 1.6e4, 0.7, 0.5), repulsive] {
            let [vx, vy, vz, wx, wy, wz] = &vw;
            let view = PairView {
                x: [&x, &y, &z],
                v: [vx, vy, vz],
                w: [wx, wy, wz],
                radius: &radius,
                i: &i,
                j: &j,
                shift: &shift,
                sqrt_m: &sqrt_m,
                r_eff: &r_eff,
                law: &law,
                dt: 5e-5,
            };
            // a pair out of contact at the last step holds zeros; one in contact a history
            // and a force
            let was: Vec<bool> = (0..np).map(|_| u(0.0, 1.0) < 0.6).collect();
            let hist: Vec<[f64; 3]> =
                was.iter().map(|&w| if w { [0; 3].map(|_| u(-2e-3, 2e-3)) } else { [0.0; 3] }).collect();
            let slot: Vec<[f64; 3]> = was.iter().map(|&w| if w { [1.0, -2.0, 3.0] } else { [0.0; 3] }).collect();

            let (mut h_ref, mut f_ref, mut t_ref) = (hist.clone(), slot.clone(), slot.clone());
            let mut touch_ref = Vec::new();
            for q in 0..np {
                if let Some((d, f, power)) = view.write(q, &mut h_ref[q], &mut f_ref[q], &mut t_ref[q]) {
                    touch_ref.push((q, d, f, power));
                }
            }
            let (mut h, mut f, mut t, mut w) = (hist, slot.clone(), slot, was);
            let mut touch = Vec::new();
            view.linear_pairs(0, PairOut { hist: &mut h, f: &mut f, t: &mut t, was: &mut w }, |c| touch.push(c));

            let bits = |v: &[[f64; 3]]| v.iter().flatten().map(|a| a.to_bits()).collect::<Vec<_>>();
            assert!(touch_ref.len() > np / 3 && touch_ref.len() < 2 * np / 3, "{} contacts", touch_ref.len());
            // both regimes of the Coulomb slider are exercised: |F_t| at mu max(F_n, 0), and below
            let sliding = touch_ref
                .iter()
                .filter(|(_, d, f, _)| {
                    let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    let n = d.map(|c| c / dist);
                    let fn_ = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]);
                    let ft = [0, 1, 2].map(|k| f[k] + fn_ * n[k]);
                    (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]).sqrt() >= law.friction * fn_.max(0.0) * (1.0 - 1e-9)
                })
                .count();
            assert!(sliding > 10 && sliding + 10 < touch_ref.len(), "{sliding} of {} sliding", touch_ref.len());
            assert_eq!(bits(&h), bits(&h_ref), "histories");
            assert_eq!(bits(&f), bits(&f_ref), "forces");
            assert_eq!(bits(&t), bits(&t_ref), "torques");
            assert_eq!(touch.len(), touch_ref.len());
            for (c, r) in touch.iter().zip(&touch_ref) {
                assert_eq!(c.0, r.0);
                assert_eq!(bits(&[c.1, c.2]), bits(&[r.1, r.2]), "pair {}", r.0);
                assert_eq!(c.3.to_bits(), r.3.to_bits(), "power of pair {}", r.0);
            }
            assert_eq!(w, (0..np).map(|q| touch_ref.iter().any(|c| c.0 == q)).collect::<Vec<_>>());
            // the repulsive law's clipped branch is exercised: contacts whose pull it removed
            let clipped = touch_ref
                .iter()
                .filter(|(_, d, f, power)| {
                    let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    let fn_ = -(f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / dist;
                    fn_ == 0.0 && *power == 0.0
                })
                .count();
            assert_eq!(clipped > 10, law.repulsive, "{clipped} clipped contacts");
        }
    }
}
