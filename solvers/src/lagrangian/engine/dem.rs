//! The dry DEM engine: contacts, walls, body forces and the leapfrog integrator.
//!
//! One step of [`Dem::step`]:
//!
//! 1. rebuild the Verlet list when a particle moved more than half the skin (the skin
//!    adapted to the motion at each rebuild, [`super::neighbours`]);
//! 2. pair forces, in parallel over fixed chunks of pairs (each pair owns its history and
//!    its output slot);
//! 3. per mobile particle, in parallel over fixed chunks: gather the pair forces (own
//!    pairs, then reverse pairs, in index order), wall contacts, body force and the
//!    external (fluid) force set by the caller, then the centred (leapfrog) update
//!    v(t + dt/2) = v(t - dt/2) + F(t)/m dt, x(t + dt) = x(t) + v(t + dt/2) dt, the same
//!    for the angular velocity with I = (2/5) m R^2 (Maurin et al. 2015 section II D: the
//!    explicit second-order centred scheme of Yade).
//!
//! Velocities in the damping terms are those of the half step before (first order in dt
//! for the dashpot, exact for the springs). No step allocates once the buffers reached
//! their working size; every sum is taken in a fixed order, so the state after a step
//! does not depend on the number of threads.

use std::time::Instant;

use rayon::prelude::*;

use crate::run::timing::Stages;

use super::chunks::{chunks_per_task, CHUNK};
use super::contact::{contact_force, cross, ContactInput, ContactLaw, ContactModel};
use super::contact_sums::{contact_values, spread, ContactSums, End, Slices, WallRecord, GROUP};
use super::cylinders::{HalfCylinders, Sphere, Touches};
use super::neighbours::NeighbourList;
use super::pairs::{Contact, PairOut, PairView};
use super::particles::{Box3, Particles};
use super::scratch::Scratch;
pub use super::scratch::STAGES;
use super::walls::{Wall, MAX_WALLS};

/// The DEM engine: its parameters (box, contact law, walls, bottom, time step: set once
/// from the scene, carried in a checkpoint with the state so that a restore can be
/// checked against the scene), its state (particles, neighbour list with the pairs'
/// springs, the walls' and cylinders' springs, body force; no clock: the steps and the
/// time are the solver's state's) and its scratch (refilled by every step, never saved).
/// The coupled solver reaches into the particles and the body force; everyone else reads
/// it through its methods.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Dem {
    /// periodic box
    bx: Box3,
    /// contact law
    law: ContactLaw,
    /// friction of the particles on the flat walls when it is not the particle law's
    #[serde(default)]
    wall_friction: Option<f64>,
    /// flat walls
    walls: Vec<Wall>,
    /// the half-cylinders of the bottom, if any
    #[serde(default)]
    cylinders: Option<HalfCylinders>,
    /// time step (s)
    dt: f64,
    /// particles
    pub(crate) p: Particles,
    /// body acceleration of mobile particles: gravity and buoyancy (m/s^2)
    pub(crate) body: [f64; 3],
    /// neighbour list and pair histories
    list: NeighbourList,
    /// history of the wall contacts of each mobile particle
    wall_hist: Vec<[[f64; 3]; MAX_WALLS]>,
    /// history of the cylinder contacts of each mobile particle (sized with the mobile
    /// particles whether or not there are cylinders: the integration zips it)
    #[serde(default)]
    cyl_hist: Vec<Touches>,
    /// a particle moved more than half the skin since the last build (set by the
    /// integration, so the check costs no extra pass)
    rebuild_due: bool,
    #[serde(skip)]
    work: Scratch,
}

impl Dem {
    /// A DEM engine; `skin` is the surface distance of the Verlet list (m).
    pub fn new(p: Particles, bx: Box3, law: ContactLaw, walls: Vec<Wall>, body: [f64; 3], dt: f64, skin: f64) -> Self {
        let nm = p.n_mobile;
        Self {
            p,
            bx,
            law,
            wall_friction: None,
            walls,
            body,
            dt,
            list: NeighbourList::new(skin),
            wall_hist: vec![[[0.0; 3]; MAX_WALLS]; nm],
            cylinders: None,
            cyl_hist: vec![Touches::default(); nm],
            rebuild_due: true,
            work: Scratch::new(nm),
        }
    }

    /// The same engine with the half-cylinders `c` as its bottom (fixed, with the flat
    /// walls).
    pub fn with_cylinders(mut self, c: Option<HalfCylinders>) -> Self {
        self.cylinders = c;
        self
    }

    /// The same engine with a friction coefficient of the particles on the flat walls
    /// other than the particle law's (None: the particle law's).
    pub fn with_wall_friction(mut self, mu: Option<f64>) -> Self {
        self.wall_friction = mu;
        self
    }

    /// The half-cylinders of the bottom, if any.
    pub fn cylinders(&self) -> Option<&HalfCylinders> {
        self.cylinders.as_ref()
    }

    /// Whether `other` has the same box, flat walls, kind of bottom and wall friction:
    /// whether this engine's particles and contact histories mean the same in it.
    pub fn same_bounds(&self, other: &Dem) -> bool {
        self.bx == other.bx
            && self.walls == other.walls
            && self.cylinders.is_some() == other.cylinders.is_some()
            && self.wall_friction == other.wall_friction
    }

    /// Particles.
    pub fn particles(&self) -> &Particles {
        &self.p
    }
    /// Time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Neighbour list and pair histories.
    pub fn list(&self) -> &NeighbourList {
        &self.list
    }
    /// Body acceleration of the mobile particles (m/s^2).
    pub fn body(&self) -> [f64; 3] {
        self.body
    }
    /// External (fluid) force per mobile particle (N), one slice per component, for the
    /// caller to fill before [`Dem::step`].
    pub fn external_force_mut(&mut self) -> &mut [Vec<f64>; 3] {
        if self.work.ext[0].len() != self.p.n_mobile {
            self.work.fit(self.p.n_mobile);
        }
        &mut self.work.ext
    }

    /// The particles, to read, beside the external force to fill from them (the drag).
    pub fn particles_and_external_force(&mut self) -> (&Particles, &mut [Vec<f64>; 3]) {
        self.external_force_mut();
        (&self.p, &mut self.work.ext)
    }

    /// After particles were added, removed or renumbered: resize the per-particle buffers
    /// and forget every contact history.
    pub fn reset_topology(&mut self) {
        let nm = self.p.n_mobile;
        self.work.fit(nm);
        self.wall_hist.clear();
        self.wall_hist.resize(nm, [[0.0; 3]; MAX_WALLS]);
        self.cyl_hist.clear();
        self.cyl_hist.resize(nm, Touches::default());
        self.list.forget();
        self.rebuild_due = true;
    }

    /// Advance one time step.
    pub fn step(&mut self) {
        self.step_sampled(None);
    }

    /// Advance one time step; with `slices`, also take the contact sums of the granular
    /// fields on them ([`super::contact_sums`]), read afterwards with [`Dem::contact_sums`].
    pub fn step_sampled(&mut self, slices: Option<Slices>) {
        let mut t = Instant::now();
        if self.rebuild_due || self.list.x0.len() != self.p.len() {
            self.list.build(&mut self.p, &self.bx);
            t = self.work.stages.lap(0, t);
        }
        if self.work.ext[0].len() != self.p.n_mobile {
            // a restored engine's scratch is empty
            self.work.fit(self.p.n_mobile);
        }
        if self.cyl_hist.len() != self.p.n_mobile {
            // a checkpoint from before the cylinders holds none
            self.cyl_hist.resize(self.p.n_mobile, Touches::default());
        }
        if let Some(s) = slices {
            self.work.contact.prepare(s, self.list.len(), self.p.n_mobile);
        }
        self.pair_forces(slices.is_some());
        let t = self.work.stages.lap(1, t);
        self.rebuild_due = self.integrate(slices.is_some());
        self.work.stages.lap(2, t);
        self.list.tick();
    }

    /// Wall time of the stages of the steps so far ([`STAGES`]; not part of the state: a
    /// restored engine counts from zero).
    pub fn stages(&self) -> &Stages {
        &self.work.stages
    }

    /// The contact sums of the last sampled step.
    pub fn contact_sums(&self) -> &ContactSums {
        &self.work.contact
    }

    fn pair_forces(&mut self, sampled: bool) {
        let np = self.list.len();
        self.work.pair_f.resize(np, [0.0; 3]);
        self.work.pair_t.resize(np, [0.0; 3]);
        // the linear law in three passes, its force loop vectorised ([`super::pairs`]);
        // the rotated spring, an option for studies of the contact law, pair by pair
        let lanes = self.law.model == ContactModel::Linear && !self.law.rotate_history;
        let p = &self.p;
        let l = &mut self.list;
        let view = PairView {
            x: [&p.x, &p.y, &p.z],
            v: [&p.vx, &p.vy, &p.vz],
            w: [&p.wx, &p.wy, &p.wz],
            radius: &p.radius,
            i: &l.i,
            j: &l.j,
            shift: &l.shift,
            sqrt_m: &l.sqrt_m,
            r_eff: &l.r_eff,
            law: &self.law,
            dt: self.dt,
        };
        let (li, lj) = (&l.i, &l.j);
        let write =
            |q: usize, h: &mut [f64; 3], f_out: &mut [f64; 3], t_out: &mut [f64; 3]| view.write(q, h, f_out, t_out);
        let was = self.work.touching.prepare(l);
        if !sampled {
            // each pair owns its history, its output slots and its flag: chunks of the
            // four arrays zipped, pair q = chunk start + k
            let pairs = (l.hist.par_chunks_mut(CHUNK), self.work.pair_f.par_chunks_mut(CHUNK));
            (pairs, self.work.pair_t.par_chunks_mut(CHUNK), was.par_chunks_mut(CHUNK))
                .into_par_iter()
                .enumerate()
                .with_max_len(chunks_per_task())
                .for_each(|(c, ((hist, pf), pt, was))| {
                    let o = c * CHUNK;
                    if lanes {
                        view.linear_pairs(o, PairOut { hist, f: pf, t: pt, was }, |_| {});
                        return;
                    }
                    for (k, ((h, f_out), t_out)) in hist.iter_mut().zip(pf.iter_mut()).zip(pt.iter_mut()).enumerate() {
                        write(o + k, h, f_out, t_out);
                    }
                });
            return;
        }
        // the same in groups of GROUP pairs, each adding its contacts to its own slab
        let cs = &mut self.work.contact;
        let (slices, slab_len) = (cs.slices, cs.slab_len());
        (
            l.hist.par_chunks_mut(GROUP),
            self.work.pair_f.par_chunks_mut(GROUP),
            self.work.pair_t.par_chunks_mut(GROUP),
            was.par_chunks_mut(GROUP),
            cs.slabs.par_chunks_mut(slab_len.max(1)),
        )
            .into_par_iter()
            .enumerate()
            .with_max_len(chunks_per_task())
            .for_each(|(c, (hist, pf, pt, was, slab))| {
                let o = c * GROUP;
                let mut add = |(q, d, f, power): Contact| {
                    let (a, b) = (li[q] as usize, lj[q] as usize);
                    let values =
                        contact_values(d, f, [p.vx[a], p.vy[a], p.vz[a]], [p.vx[b], p.vy[b], p.vz[b]], power, 1.0);
                    let ends = (End { z: p.z[a], r: p.radius[a] }, End { z: p.z[a] + d[2], r: p.radius[b] });
                    spread(&slices, slab, ends.0, ends.1, &values);
                };
                if lanes {
                    view.linear_pairs(o, PairOut { hist, f: pf, t: pt, was }, add);
                    return;
                }
                for (k, ((h, f_out), t_out)) in hist.iter_mut().zip(pf.iter_mut()).zip(pt.iter_mut()).enumerate() {
                    let q = o + k;
                    if let Some((d, f, power)) = write(q, h, f_out, t_out) {
                        add((q, d, f, power));
                    }
                }
            });
    }

    /// Leapfrog update of the mobile particles; true when one of them moved more than half
    /// the skin since the last neighbour build.
    fn integrate(&mut self, sampled: bool) -> bool {
        let nm = self.p.n_mobile;
        let dt = self.dt;
        let body = self.body;
        let law = &self.law;
        // the particle law with the walls' friction, derived once per step
        let wall_law = &self.wall_friction.map_or(*law, |friction| ContactLaw { friction, ..*law });
        let walls = &self.walls;
        let cylinders = self.cylinders.as_ref();
        let l = &self.list;
        let (pf, pt) = (&self.work.pair_f, &self.work.pair_t);
        let ext = &self.work.ext;
        let ext_t = &self.work.ext_torque;
        let p = &mut self.p;
        let (radius, inv_m, inv_i) = (&p.radius, &p.inv_mass, &p.inv_inertia);
        let x0 = &l.x0;
        let lim = 0.25 * l.skin * l.skin;
        fn chunks(v: &mut [f64], nm: usize) -> rayon::slice::ChunksMut<'_, f64> {
            v[..nm].par_chunks_mut(CHUNK)
        }
        // the positions, velocities, spins and wall histories of a chunk of mobile
        // particles, zipped: particle a = chunk start + k
        let pos = (chunks(&mut p.x, nm), chunks(&mut p.y, nm), chunks(&mut p.z, nm));
        let vel = (chunks(&mut p.vx, nm), chunks(&mut p.vy, nm), chunks(&mut p.vz, nm));
        let spin = (chunks(&mut p.wx, nm), chunks(&mut p.wy, nm), chunks(&mut p.wz, nm));
        let wall_hist = self.wall_hist[..nm].par_chunks_mut(CHUNK);
        let cyl_hist = self.cyl_hist[..nm].par_chunks_mut(CHUNK);
        // the wall contacts' records of a sampled step, none otherwise
        let recorded = if sampled { nm } else { 0 };
        let unrecorded = nm.div_ceil(CHUNK) - recorded.div_ceil(CHUNK);
        let records = self.work.contact.walls[..recorded]
            .par_chunks_mut(CHUNK)
            .map(Some)
            .chain((0..unrecorded).into_par_iter().map(|_| None));
        (pos.into_par_iter(), vel.into_par_iter(), spin.into_par_iter(), wall_hist, cyl_hist, records)
            .into_par_iter()
            .enumerate()
            .with_max_len(chunks_per_task())
            .map(|(c, ((x, y, z), (vx, vy, vz), (wx, wy, wz), wh, ch, mut rec))| {
                let o = c * CHUNK;
                let mut moved = false;
                for k in 0..x.len() {
                    let a = o + k;
                    let ra = radius[a];
                    let mut f = [ext[0][a], ext[1][a], ext[2][a]];
                    let mut t = [ext_t[0][a], ext_t[1][a], ext_t[2][a]];
                    for q in l.start[a]..l.start[a + 1] {
                        let (fq, tq) = (pf[q], pt[q]);
                        for c in 0..3 {
                            f[c] += fq[c];
                            t[c] += ra * tq[c];
                        }
                    }
                    for &q in &l.rev[l.rev_start[a]..l.rev_start[a + 1]] {
                        let (fq, tq) = (pf[q as usize], pt[q as usize]);
                        for c in 0..3 {
                            f[c] -= fq[c];
                            t[c] += ra * tq[c];
                        }
                    }
                    let pos = [x[k], y[k], z[k]];
                    for (w, wall) in walls.iter().enumerate() {
                        let gap = (pos[wall.axis] - wall.position) * wall.sign;
                        let delta = ra - gap;
                        let h = &mut wh[k][w];
                        if delta <= 0.0 {
                            *h = [0.0; 3];
                            continue;
                        }
                        let mut n = [0.0; 3];
                        n[wall.axis] = -wall.sign;
                        let spin = cross([ra * wx[k], ra * wy[k], ra * wz[k]], n);
                        let v_rel = [-vx[k] - spin[0], -vy[k] - spin[1], -vz[k] - spin[2]];
                        let spin_n = 0.5 * (wx[k] * n[0] + wy[k] * n[1] + wz[k] * n[2]);
                        let c = ContactInput { n, delta, v_rel, sqrt_m: (1.0 / inv_m[a]).sqrt(), r_eff: ra, spin_n };
                        let (fw, power) = contact_force(wall_law, &c, h, dt);
                        let tw = cross(n, fw);
                        if let Some(rec) = rec.as_deref_mut() {
                            // branch from the centre to the wall plane, the wall at rest
                            let arm = [n[0] * gap, n[1] * gap, n[2] * gap];
                            let values = contact_values(arm, fw, [vx[k], vy[k], vz[k]], [0.0; 3], power, 0.5);
                            let r: &mut WallRecord = &mut rec[k][w];
                            r[..3].copy_from_slice(&[pos[2], ra, pos[2] + arm[2]]);
                            r[3..].copy_from_slice(&values);
                        }
                        for c in 0..3 {
                            f[c] += fw[c];
                            t[c] += ra * tw[c];
                        }
                    }
                    if let Some(cyl) = cylinders {
                        let s = Sphere {
                            x: pos,
                            v: [vx[k], vy[k], vz[k]],
                            w: [wx[k], wy[k], wz[k]],
                            r: ra,
                            sqrt_m: (1.0 / inv_m[a]).sqrt(),
                        };
                        cyl.add_forces(&s, law, dt, &mut ch[k], (&mut f, &mut t), |slot, (arm, fc, power)| {
                            if let Some(rec) = rec.as_deref_mut() {
                                let values = contact_values(arm, fc, s.v, [0.0; 3], power, 0.5);
                                let r: &mut WallRecord = &mut rec[k][MAX_WALLS + slot];
                                r[..3].copy_from_slice(&[pos[2], ra, pos[2] + arm[2]]);
                                r[3..].copy_from_slice(&values);
                            }
                        });
                    }
                    let im = inv_m[a];
                    let ii = inv_i[a];
                    vx[k] += (f[0] * im + body[0]) * dt;
                    vy[k] += (f[1] * im + body[1]) * dt;
                    vz[k] += (f[2] * im + body[2]) * dt;
                    wx[k] += t[0] * ii * dt;
                    wy[k] += t[1] * ii * dt;
                    wz[k] += t[2] * ii * dt;
                    x[k] += vx[k] * dt;
                    y[k] += vy[k] * dt;
                    z[k] += vz[k] * dt;
                    let a0 = x0[a];
                    moved |= (x[k] - a0[0]).powi(2) + (y[k] - a0[1]).powi(2) + (z[k] - a0[2]).powi(2) > lim;
                }
                moved
            })
            .reduce(|| false, |a, b| a || b)
    }

    /// Elastic energy stored in the normal springs of the linear law (J), for energy
    /// checks: sum over contacts of k_n delta^2 / 2 (walls included).
    pub fn normal_spring_energy(&self) -> f64 {
        let mut e = 0.0;
        self.each_overlap(|_, delta, _| e += 0.5 * self.law.kn * delta * delta);
        e
    }

    /// The deepest overlap over the diameter of the smaller grain of its contact (walls
    /// and half-cylinders included), with a mobile particle of that contact; `None`
    /// without contacts.
    pub fn deepest_overlap(&self) -> Option<(usize, f64)> {
        let mut deepest: Option<(usize, f64)> = None;
        self.each_overlap(|a, delta, d| {
            let f = delta / d;
            if !matches!(deepest, Some((_, g)) if g >= f) {
                deepest = Some((a, f));
            }
        });
        deepest
    }

    /// Call `f(a, delta, d)` for every contact in overlap delta > 0 (m): the pairs of the
    /// neighbour list, then each mobile particle's walls and half-cylinders; a is a mobile
    /// particle of the contact and d the smaller diameter of its grains.
    fn each_overlap(&self, mut f: impl FnMut(usize, f64, f64)) {
        let p = &self.p;
        let l = &self.list;
        for q in 0..l.len() {
            let (a, b) = (l.i[q] as usize, l.j[q] as usize);
            let s = l.shift[q];
            let d = [p.x[b] + s[0] - p.x[a], p.y[b] + s[1] - p.y[a], p.z[b] + s[2] - p.z[a]];
            let delta = p.radius[a] + p.radius[b] - (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if delta > 0.0 {
                let mobile = if a < p.n_mobile { a } else { b };
                f(mobile, delta, 2.0 * p.radius[a].min(p.radius[b]));
            }
        }
        for a in 0..p.n_mobile {
            let pos = [p.x[a], p.y[a], p.z[a]];
            for wall in &self.walls {
                let delta = p.radius[a] - (pos[wall.axis] - wall.position) * wall.sign;
                if delta > 0.0 {
                    f(a, delta, 2.0 * p.radius[a]);
                }
            }
            if let Some(c) = &self.cylinders {
                c.each_overlap(pos, p.radius[a], |delta| f(a, delta, 2.0 * p.radius[a].min(c.radius)));
            }
        }
    }

    /// First mobile particle whose position or velocity is not finite, with the field.
    pub fn first_non_finite(&self) -> Option<(usize, &'static str, f64)> {
        let p = &self.p;
        let fields: [(&'static str, &Vec<f64>); 9] = [
            ("x", &p.x),
            ("y", &p.y),
            ("z", &p.z),
            ("v_x", &p.vx),
            ("v_y", &p.vy),
            ("v_z", &p.vz),
            ("omega_x", &p.wx),
            ("omega_y", &p.wy),
            ("omega_z", &p.wz),
        ];
        for a in 0..p.n_mobile {
            for (name, v) in fields {
                if !v[a].is_finite() {
                    return Some((a, name, v[a]));
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests;
