//! Fluid force on each particle: drag with the column velocity at the particle centre or
//! averaged over the particle (`solver.lagrangian.drag_velocity`) plus the fluctuation
//! closure's stochastic velocity (Maurin et al. 2015 eqs 11-12, 15-16; Chassagne et al.
//! 2023 eq 2.26).
//!
//! ```text
//! F_D = (1/2) rho_f (pi d^2 / 4) f(phi, Re_p) C_D(Re*) |u_r| u_r,
//! u_r = u_f(z_p) e_x + u'  - v_p,   Re_p = |u_r| d / nu_f,   Re* = hindrance convention
//! ```
//!
//! written F_D = k_p u_r with k_p = (pi/8) rho_f nu_f d C_D(Re*) Re_p f, finite as
//! |u_r| -> 0. u_f(z_p) is, with `drag_velocity = "centre"` (the default, Maurin eq 11 as
//! the reference YADE code), the column velocity at the centre interpolated linearly
//! between cell centres (0 at the column bottom and below it, the top cell's value above
//! the last centre); with `"sphere_average"`, the column velocity averaged over the sphere
//! with the slice volumes of the averaging, sum_c (V_pc / V_p) u_c
//! ([`FluidField::sphere_velocity`]: the centre value for a profile linear across the
//! grain; parts outside the column see the fluid at rest), so that the exchange of
//! `averaging.rs` hands the fluid exactly the grains' drag. phi is the volume fraction of
//! the cell holding the centre (as Maurin's implementation). Buoyancy is part of the body
//! force ([`crate::lagrangian::run::setup::body_acceleration`]).
//!
//! The closures are called once per chunk of particles through their batch methods
//! (C_D over Re*, f over (phi, Re_p)); Re* = c(phi) Re_p with c the ratio of the
//! hindrance's declared convention ([`saltus_core::Hindrance::reynolds_convention`], the
//! same [`crate::inputs::DragKernel`] convention as the Eulerian solver's), stored per
//! cell. A hindrance that declares no Re_p dependence (Richardson-Zaki) is evaluated per
//! cell at each fluid update instead of per particle and step (the particle's phi is its
//! cell's anyway).
//!
//! The particle Reynolds number of C_D and of the hindrance is that of u_r, unless the
//! fluctuation closure asks for the mean slip ([`saltus_core::SlipReynolds::Mean`], key
//! `drag_reynolds = "mean"` of `eim`: Cheng, Chauchat, Hsu & Calantoni eq 7, Re_p =
//! |u_f - v| d / nu_f without u', the force of their eq 6 keeping |u_r| u_r): then
//! k_p = (pi/8) rho_f nu_f d C_D(Re*_mean) Re_inst f(phi, Re_mean). Where the mean slip
//! vanishes and u' does not (a grain at rest in the bed under a draw), that k_p grows
//! without bound (C_D Re_mean -> 24 while Re_inst stays), so it is capped at m_p / dt, the
//! largest coefficient the explicit DEM step keeps stable.
//!
//! Fluctuations (`drw` now, any [`saltus_core::Fluctuation`]): each particle carries its
//! own draw and the time left before the next one, and its own random stream
//! `stream(seed, particle index)`, so the draws do not depend on the thread count. The
//! first duration is cut by a uniform random fraction so that the particles do not redraw
//! in step (the random phase the closure's documentation asks for).

use rand::Rng as _;
use saltus_core::grain::ball_volume;
use saltus_core::rng::{stream, Rng};
use saltus_core::scene::DragVelocity;
use saltus_core::{
    DragLaw, FlowScales, Fluctuation, FluctuationDraw, Hindrance, ParticleSlip, SlipReynolds, TurbulencePoint,
};

use rayon::prelude::*;

use crate::lagrangian::engine::chunks::{chunks_per_task, CHUNK};
use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::engine::slicing::sphere_slices;
use saltus_core::grain::sphere_volume;

/// Largest column height, in grain radii, for which [`FluidField::sphere_velocity`] uses
/// the moments of the column (case 1: 63, Fry's Couette: 41).
pub const MOMENT_SPAN: f64 = 80.0;

/// Fluid fields the particles see, on the column's cells (uniform grid from z = `base`).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct FluidField {
    /// height of the column bottom in particle coordinates (m): the top of the rough layer
    pub base: f64,
    /// cell height (m)
    pub dz: f64,
    /// streamwise fluid velocity per cell centre (m/s)
    pub u: Vec<f64>,
    /// volume fraction per cell
    pub phi: Vec<f64>,
    /// kinematic Reynolds shear stress R_xz / (rho_f eps) per cell (m^2/s^2)
    pub reynolds: Vec<f64>,
    /// eddy viscosity per cell (m^2/s)
    pub nu_t: Vec<f64>,
    /// turbulent kinetic energy and specific dissipation rate per cell, when the column
    /// transports them (k-omega; the eddy interaction model draws from them); empty
    /// otherwise
    pub k_omega: [Vec<f64>; 2],
    /// Re* / Re_p per cell (the hindrance's declared convention)
    pub re_ratio: Vec<f64>,
    /// hindrance factor per cell, when the hindrance does not depend on Re_p (then the
    /// particles read it instead of evaluating the closure); empty otherwise
    pub hindrance: Vec<f64>,
    /// water depth and bulk velocity for the eddy turnover time
    pub scales: FlowScales,
    /// int_0^{j dz} u z^m dz at the faces j = 0..=n, m = 0, 1, 2: derived from `u` by
    /// [`Self::refresh`] (not saved; a restored field is refreshed)
    #[serde(skip)]
    moments: [Vec<f64>; 3],
    /// height above `base` below which the fluctuation draws are spared
    /// ([`saltus_core::Fluctuation::above_bed`]), derived from `phi` by
    /// [`Self::set_bed_threshold`] once per fluid update rather than at each of the grains'
    /// draws; -inf when the draws apply everywhere (not saved; a restored field is set again)
    #[serde(skip)]
    drw_floor: f64,
}

impl FluidField {
    /// Fluid at rest over `n` cells of height `dz` above `base`.
    pub fn at_rest(n: usize, dz: f64, base: f64) -> Self {
        Self {
            base,
            dz,
            u: vec![0.0; n],
            phi: vec![0.0; n],
            reynolds: vec![0.0; n],
            nu_t: vec![0.0; n],
            k_omega: [Vec::new(), Vec::new()],
            re_ratio: vec![1.0; n],
            hindrance: Vec::new(),
            scales: FlowScales::default(),
            moments: [vec![0.0; n + 1], vec![0.0; n + 1], vec![0.0; n + 1]],
            drw_floor: f64::NEG_INFINITY,
        }
    }

    /// Derive from `phi` the height below which fluctuation draws are spared: the top of
    /// the highest peak of phi above `threshold` ([`crate::inputs::peak_bed_elevation`]),
    /// or nowhere for `None`. Call after `phi` changes.
    pub fn set_bed_threshold(&mut self, threshold: Option<f64>) {
        self.drw_floor = match threshold {
            Some(phi_b) => crate::inputs::peak_bed_elevation(&self.phi, self.dz, phi_b),
            None => f64::NEG_INFINITY,
        };
    }

    /// Set the cell velocities and the moments [`Self::sphere_velocity`] reads.
    pub fn set_velocity(&mut self, u: &[f64]) {
        self.u.copy_from_slice(u);
        self.refresh();
    }

    /// Recompute the moments of `u` (after `u` was written directly, or restored).
    pub fn refresh(&mut self) {
        let dz = self.dz;
        let mut acc = [0.0; 3];
        for m in &mut self.moments {
            m.clear();
            m.push(0.0);
        }
        for (c, &u) in self.u.iter().enumerate() {
            let (lo, hi) = (c as f64 * dz, (c + 1) as f64 * dz);
            acc[0] += u * (hi - lo);
            acc[1] += u * (hi * hi - lo * lo) / 2.0;
            acc[2] += u * (hi * hi * hi - lo * lo * lo) / 3.0;
            for (m, a) in self.moments.iter_mut().zip(acc) {
                m.push(a);
            }
        }
    }

    /// int_0^h u z^m dz, m = 0, 1, 2, h from the column bottom (u = 0 outside the column).
    #[inline]
    fn integrals(&self, h: f64) -> [f64; 3] {
        let n = self.u.len();
        let h = h.clamp(0.0, n as f64 * self.dz);
        // h >= 0 (or NaN, cast to 0): truncation is the floor
        let c = ((h / self.dz) as usize).min(n - 1);
        let (lo, u) = (c as f64 * self.dz, self.u[c]);
        let [m0, m1, m2] = &self.moments;
        [m0[c] + u * (h - lo), m1[c] + u * (h * h - lo * lo) / 2.0, m2[c] + u * (h * h * h - lo * lo * lo) / 3.0]
    }

    /// Cell holding height z (clamped to the column).
    #[inline]
    pub fn cell(&self, z: f64) -> usize {
        // truncation is the floor for positive values and avoids a libm call per particle
        let k = (z - self.base) / self.dz;
        if k <= 0.0 {
            0
        } else {
            (k as usize).min(self.u.len() - 1)
        }
    }

    /// Fluid velocity at height z, linear between centres, 0 at the column bottom and
    /// below.
    #[inline]
    pub fn velocity(&self, z: f64) -> f64 {
        let z = z - self.base;
        let s = z / self.dz - 0.5;
        let n = self.u.len();
        if s <= 0.0 {
            let w = (z / (0.5 * self.dz)).clamp(0.0, 1.0);
            return w * self.u[0];
        }
        // compared as floats before the cast: a particle flung far away (s huge, inf or
        // NaN) would saturate the cast and overflow k + 1
        if s.is_nan() || s >= (n - 1) as f64 {
            return self.u[n - 1];
        }
        let k = s as usize; // 0 < s < n - 1 here: truncation is the floor
        let w = s - k as f64;
        self.u[k] + w * (self.u[k + 1] - self.u[k])
    }

    /// The fluid velocity the drag of a grain of centre height z and radius r sees:
    /// [`Self::velocity`] at its centre or [`Self::sphere_velocity`] over it.
    #[inline]
    pub fn seen(&self, mode: DragVelocity, z: f64, r: f64) -> f64 {
        match mode {
            DragVelocity::Centre => self.velocity(z),
            DragVelocity::SphereAverage => self.sphere_velocity(z, r),
        }
    }

    /// Mean fluid velocity over the sphere of centre height z and radius r,
    /// sum_c (V_pc / V_p) u_c with the slice volumes of the averaging
    /// ([`sphere_slices`]): the velocity the grains' drag sees. Being the
    /// transpose of the slice averaging, it makes the exchange hand the fluid exactly the
    /// grains' drag (see `averaging.rs`). Parts of the sphere outside the column see a
    /// fluid at rest (the no-slip bottom; the exchange drops them too).
    ///
    /// In O(1) from the moments: V_p ubar = pi int u(z') (r^2 - (z' - z)^2) dz' over the
    /// sphere, the slice volumes being the integrals of its cross-section pi (r^2 -
    /// (z' - z)^2); equal to the sum over the slices up to rounding.
    ///
    /// The moments are global, so their differences lose about (H / r)^3 of the float's
    /// precision (H the column height): above H = [`MOMENT_SPAN`] r (3e-11 of the velocity
    /// at worst) the sum runs over the slices instead.
    #[inline]
    pub fn sphere_velocity(&self, z: f64, r: f64) -> f64 {
        let z = z - self.base;
        let n = self.u.len();
        if self.moments[0].len() != n + 1 || n as f64 * self.dz > MOMENT_SPAN * r {
            // moments not refreshed since `u` changed size, or too coarse for this grain
            let mut sum = 0.0;
            sphere_slices(z, r, self.u.len(), self.dz, |c, w| sum += w * self.u[c]);
            return sum / ball_volume(r);
        }
        let (a, b) = (self.integrals(z - r), self.integrals(z + r));
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        ((r * r - z * z) * d[0] + 2.0 * z * d[1] - d[2]) / (4.0 / 3.0 * r * r * r)
    }
}

/// The closures of the fluid force.
#[derive(Clone, Copy, Debug)]
pub struct DragModels<'a> {
    /// single-particle drag
    pub drag: &'a dyn DragLaw,
    /// hindrance
    pub hindrance: &'a dyn Hindrance,
    /// fluctuations, `None` when inactive
    pub fluctuation: Option<&'a dyn Fluctuation>,
    /// the fluid velocity the drag sees
    pub velocity: DragVelocity,
}

/// Per-particle drag state and work arrays (all particles, fixed ones included: the
/// fluid sees their drag).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct FluidForces {
    /// fluid density (kg/m^3)
    pub(crate) rho_f: f64,
    /// fluid viscosity (m^2/s)
    pub(crate) nu_f: f64,
    /// particle density (kg/m^3)
    pub(crate) rho_p: f64,
    /// drag coefficient k_p with F = k_p u_r (kg/s), of the last evaluation
    pub(crate) k: Vec<f64>,
    /// streamwise relative velocity u_r,x of the last evaluation (m/s)
    pub(crate) urx: Vec<f64>,
    /// fluctuation velocity of each particle (m/s)
    pub(crate) fluct: Vec<[f64; 3]>,
    /// time left before the next draw (s); -inf before the first draw
    pub(crate) left: Vec<f64>,
    /// redraw delay when the closure gives no finite duration (s): the fluid period
    pub(crate) fallback_period: f64,
    /// no finite eddy drawn yet (the next one gets a random phase)
    fresh: Vec<bool>,
    rng: Vec<Rng>,
    re: Vec<f64>,
    re_star: Vec<f64>,
    cd: Vec<f64>,
    hind: Vec<f64>,
    phi_p: Vec<f64>,
    ur: Vec<[f64; 3]>,
}

impl FluidForces {
    /// Work arrays for `n` particles; particle k draws from `stream(seed, k)`.
    pub fn new(n: usize, seed: u64, rho_f: f64, nu_f: f64, rho_p: f64) -> Self {
        Self {
            rho_f,
            nu_f,
            rho_p,
            k: vec![0.0; n],
            urx: vec![0.0; n],
            fluct: vec![[0.0; 3]; n],
            left: vec![f64::NEG_INFINITY; n],
            fallback_period: 0.0,
            fresh: vec![true; n],
            rng: (0..n as u64).map(|k| stream(seed, k)).collect(),
            re: vec![0.0; n],
            re_star: vec![0.0; n],
            cd: vec![0.0; n],
            hind: vec![0.0; n],
            phi_p: vec![0.0; n],
            ur: vec![[0.0; 3]; n],
        }
    }

    /// Drag on particles `0..upto` (the mobile ones, or all of them at a fluid update)
    /// into `out` (one slice per component, length >= mobile count; entries of fixed
    /// particles are not written), advancing the fluctuation clocks by `dt`.
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &mut self,
        p: &Particles,
        field: &FluidField,
        models: &DragModels<'_>,
        dt: f64,
        upto: usize,
        out: &mut [Vec<f64>; 3],
    ) {
        let (rho_f, nu_f, rho_p, fallback) = (self.rho_f, self.nu_f, self.rho_p, self.fallback_period);
        let mean_re = models.fluctuation.is_some_and(|f| f.drag_reynolds() == SlipReynolds::Mean);
        let nm = p.n_mobile;
        let n_out = upto.min(nm);
        // per-particle state and scratch cut into the same fixed chunks, zipped: particle
        // a = chunk start + i; the output slots exist for mobile particles only, so the
        // chunks past them get none
        let state = (
            self.k[..upto].par_chunks_mut(CHUNK),
            self.urx[..upto].par_chunks_mut(CHUNK),
            self.fluct[..upto].par_chunks_mut(CHUNK),
            self.left[..upto].par_chunks_mut(CHUNK),
            self.fresh[..upto].par_chunks_mut(CHUNK),
            self.rng[..upto].par_chunks_mut(CHUNK),
        );
        let scratch = (
            self.re[..upto].par_chunks_mut(CHUNK),
            self.re_star[..upto].par_chunks_mut(CHUNK),
            self.cd[..upto].par_chunks_mut(CHUNK),
            self.hind[..upto].par_chunks_mut(CHUNK),
            self.phi_p[..upto].par_chunks_mut(CHUNK),
            self.ur[..upto].par_chunks_mut(CHUNK),
        );
        let [ox, oy, oz] = out;
        let with_out = n_out.div_ceil(CHUNK);
        let without = upto.div_ceil(CHUNK) - with_out;
        let outputs =
            (ox[..n_out].par_chunks_mut(CHUNK), oy[..n_out].par_chunks_mut(CHUNK), oz[..n_out].par_chunks_mut(CHUNK))
                .into_par_iter()
                .map(Some)
                .chain((0..without).into_par_iter().map(|_| None));
        (state.into_par_iter(), scratch.into_par_iter(), outputs)
            .into_par_iter()
            .enumerate()
            .with_max_len(chunks_per_task())
            .for_each(|(c, ((k, urx, fluct, left, fresh, rng), (re, re_star, cd, hind, phi_p, ur), out))| {
                let o = c * CHUNK;
                let n = k.len();
                // the fluctuation draws of the chunk, one batch: the mobile particles whose
                // eddy expired, each from its own stream (the variates of its draw, then
                // its random phase), so the draws do not depend on the chunking
                if let Some(fl) = models.fluctuation {
                    let mut due = Vec::new();
                    let (mut points, mut slips) = (Vec::new(), Vec::new());
                    for i in 0..n.min(nm.saturating_sub(o)) {
                        left[i] -= dt;
                        if left[i] > 0.0 {
                            continue;
                        }
                        let a = o + i;
                        let cell = field.cell(p.z[a]);
                        let [kf, wf] = &field.k_omega;
                        points.push(TurbulencePoint {
                            k: kf.get(cell).copied().unwrap_or(0.0),
                            omega: wf.get(cell).copied().unwrap_or(0.0),
                            nu_t: field.nu_t[cell],
                            reynolds_stress: field.reynolds[cell],
                        });
                        // slip and response time of the last evaluation, for the eddy
                        // crossing time of the eddy interaction model (Cheng eq 37)
                        let [ax, ay, az] = ur[i];
                        let slip = (ax * ax + ay * ay + az * az).sqrt();
                        let d = 2.0 * p.radius[a];
                        let response_time = if slip > 0.0 && cd[i] > 0.0 {
                            4.0 * rho_p * d / (3.0 * rho_f * cd[i] * slip)
                        } else {
                            f64::INFINITY
                        };
                        slips.push(ParticleSlip { slip, response_time });
                        due.push(i);
                    }
                    if !due.is_empty() {
                        let mut draws = vec![FluctuationDraw::default(); due.len()];
                        {
                            let mut streams: Vec<&mut Rng> = Vec::with_capacity(due.len());
                            let mut next = due.iter().peekable();
                            for (i, r) in rng.iter_mut().enumerate() {
                                if next.peek() == Some(&&i) {
                                    streams.push(r);
                                    next.next();
                                }
                            }
                            fl.draw_batch(&points, &slips, &field.scales, &mut streams, &mut draws);
                        }
                        for (&i, draw) in due.iter().zip(&draws) {
                            fluct[i] = draw.u;
                            // the peer code's DRW spares the grains inside the bed; the draw
                            // is made all the same, so the random streams do not depend on it
                            if p.z[o + i] - field.base <= field.drw_floor {
                                fluct[i] = [0.0; 3];
                            }
                            left[i] = if !draw.duration.is_finite() {
                                // no turnover time yet (flow at rest): try again at the next
                                // fluid update, still without a phase
                                fallback
                            } else if fresh[i] {
                                // first finite eddy: random phase, so that particles do not
                                // redraw in step
                                fresh[i] = false;
                                draw.duration * rng[i].gen::<f64>()
                            } else {
                                draw.duration
                            };
                        }
                    }
                }
                for i in 0..n {
                    let a = o + i;
                    let z = p.z[a];
                    let cell = field.cell(z);
                    let uf = field.seen(models.velocity, z, p.radius[a]);
                    let u = [uf + fluct[i][0] - p.vx[a], fluct[i][1] - p.vy[a], fluct[i][2] - p.vz[a]];
                    let d = 2.0 * p.radius[a];
                    re[i] = if mean_re {
                        // Cheng eq 7: Re_p of the mean slip u_f - v, without u'
                        SlipReynolds::Mean.slip(u, fluct[i]) * d / nu_f
                    } else {
                        let speed = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
                        speed * d / nu_f
                    };
                    re_star[i] = (field.re_ratio[cell] * re[i]).max(1e-12);
                    phi_p[i] = field.phi[cell];
                    // the hindrance held per cell, read here with the cell at hand
                    if let Some(&h) = field.hindrance.get(cell) {
                        hind[i] = h;
                    }
                    ur[i] = u;
                }
                models.drag.cd_batch(re_star, cd);
                if field.hindrance.is_empty() {
                    models.hindrance.factor_batch(phi_p, re, hind);
                }
                for i in 0..n {
                    let d = 2.0 * p.radius[o + i];
                    if mean_re {
                        // eq 6's force keeps the instantaneous slip: k_p = (pi/8) rho_f nu_f d
                        // C_D(Re_mean) Re_inst f(Re_mean), at most m_p / dt (module docs)
                        let [ax, ay, az] = ur[i];
                        let re_inst = (ax * ax + ay * ay + az * az).sqrt() * d / nu_f;
                        let kp = std::f64::consts::PI / 8.0 * rho_f * nu_f * d * cd[i] * re_inst * hind[i];
                        k[i] = kp.min(rho_p * sphere_volume(d) / dt);
                    } else {
                        k[i] = std::f64::consts::PI / 8.0 * rho_f * nu_f * d * cd[i] * re[i] * hind[i];
                    }
                    urx[i] = ur[i][0];
                }
                if let Some((ox, oy, oz)) = out {
                    for i in 0..ox.len() {
                        ox[i] = k[i] * ur[i][0];
                        oy[i] = k[i] * ur[i][1];
                        oz[i] = k[i] * ur[i][2];
                    }
                }
            });
    }

    /// Restart every fluctuation clock (first draw with a random phase at the next
    /// evaluation), e.g. when the flow starts.
    pub fn restart_fluctuations(&mut self) {
        self.left.fill(f64::NEG_INFINITY);
        self.fluct.fill([0.0; 3]);
        self.fresh.fill(true);
    }

    /// Fluctuation velocity of each particle (m/s).
    pub fn fluctuations(&self) -> &[[f64; 3]] {
        &self.fluct
    }

    /// Time left before each particle's next fluctuation draw (s); -inf before the first.
    pub fn eddy_clocks(&self) -> &[f64] {
        &self.left
    }

    /// Fluid force k_p u_r on particle `a` of the last evaluation that included it (N);
    /// zero before any.
    #[inline]
    pub fn force(&self, a: usize) -> [f64; 3] {
        let (k, u) = (self.k[a], self.ur[a]);
        [k * u[0], k * u[1], k * u[2]]
    }

    /// Particle response time m / k_p of particle `a` (s), for diagnostics.
    pub fn response_time(&self, p: &Particles, a: usize) -> f64 {
        let m = self.rho_p * sphere_volume(2.0 * p.radius[a]);
        m / self.k[a]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use saltus_closures::drag::HaiderLevenspiel;
    use saltus_closures::fluctuation::{DragReynoldsNumber, EddyInteraction};
    use saltus_closures::hindrance::DiFelice;

    const R: f64 = 1.5e-3;
    const RHO_P: f64 = 1192.0;
    const DT: f64 = 1e-4;

    /// Streamwise force on grains at rest mid-column in a uniform fluid `u`, each with its
    /// own streamwise fluctuation `fl` held (no redraw), under the `eim` closure's
    /// `drag_reynolds`.
    fn forces(u: f64, fl: &[f64], form: DragReynoldsNumber) -> Vec<f64> {
        let (n_cells, dz) = (20, 1e-3);
        let mut field = FluidField::at_rest(n_cells, dz, 0.0);
        field.set_velocity(&vec![u; n_cells]);
        let mut p = Particles::default();
        for _ in fl {
            p.push([0.0, 0.0, 0.01], [0.0; 3], [0.0; 3], R, RHO_P, false);
        }
        let mut f = FluidForces::new(fl.len(), 1, 1000.0, 1e-6, RHO_P);
        for (i, &a) in fl.iter().enumerate() {
            f.fluct[i] = [a, 0.0, 0.0];
            f.left[i] = 1e9;
        }
        let (drag, hindrance) = (HaiderLevenspiel { sphericity: 0.594 }, DiFelice::default());
        let eim = EddyInteraction { drag_reynolds: form, ..EddyInteraction::default() };
        let models =
            DragModels { drag: &drag, hindrance: &hindrance, fluctuation: Some(&eim), velocity: DragVelocity::Centre };
        let mut out = [vec![0.0; fl.len()], vec![0.0; fl.len()], vec![0.0; fl.len()]];
        f.evaluate(&p, &field, &models, DT, fl.len(), &mut out);
        out[0].clone()
    }

    /// F / (|u_r| u_r) = (1/2) rho_f C_D f A of each grain (u_r = u + u' streamwise here).
    fn coefficients(u: f64, fl: &[f64], f: &[f64]) -> Vec<f64> {
        fl.iter().zip(f).map(|(a, f)| f / ((u + a).abs() * (u + a))).collect()
    }

    #[test]
    fn under_eq_7_the_drag_coefficient_does_not_see_the_fluctuation() {
        // Cheng eq 7: C_D and the hindrance at the mean slip, eq 6's force at u_r: the
        // coefficient F / (|u_r| u_r) is the same for u' = +a, -a and 0
        for (u, a) in [(0.3, 0.1), (0.05, 0.04), (1.0, 0.5)] {
            let fl = [a, -a, 0.0];
            let c = coefficients(u, &fl, &forces(u, &fl, DragReynoldsNumber::Mean));
            assert!((c[0] / c[2] - 1.0).abs() < 1e-12 && (c[1] / c[2] - 1.0).abs() < 1e-12, "u {u}, u' {a}: {c:?}");
        }
    }

    #[test]
    fn with_the_instantaneous_reynolds_number_the_drag_coefficient_follows_the_draw() {
        // C_D(Re_p) f(Re_p) of the slip with u': a draw along the slip and one against it
        // move the coefficient away from the mean slip's (for sphericity 0.594 C_D f has a
        // minimum at Re_p of a few hundred, eqs 7-13), by a margin the draw sets
        for (u, a) in [(0.3, 0.1), (0.05, 0.04), (1.0, 0.5)] {
            let fl = [a, -a, 0.0];
            let c = coefficients(u, &fl, &forces(u, &fl, DragReynoldsNumber::Instantaneous));
            assert!((c[0] / c[2] - 1.0).abs() > 1e-3 && (c[1] / c[2] - 1.0).abs() > 1e-3, "u {u}, u' {a}: {c:?}");
        }
        // and the two forms agree without a fluctuation
        let (i, m) =
            (forces(0.3, &[0.0], DragReynoldsNumber::Instantaneous), forces(0.3, &[0.0], DragReynoldsNumber::Mean));
        assert_eq!(i, m);
    }

    #[test]
    fn a_fluctuation_on_a_grain_moving_with_the_mean_fluid_gets_a_bounded_coefficient() {
        // mean slip 0, u' = 0.1 m/s: eq 7's C_D(Re_mean -> 0) Re_inst has no bound; the
        // coefficient is capped at m_p / dt, finite and positive
        let f = forces(0.0, &[0.1], DragReynoldsNumber::Mean);
        let m = RHO_P * sphere_volume(2.0 * R);
        assert!(f[0].is_finite() && f[0] > 0.0 && f[0] <= m / DT * 0.1 * (1.0 + 1e-12), "{f:?}");
    }
}
