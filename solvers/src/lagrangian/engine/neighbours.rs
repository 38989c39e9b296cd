//! Verlet neighbour list with a skin, built with a cell list, carrying the contact
//! history of every pair.
//!
//! The list holds every pair (i < j, not both fixed) whose surfaces are closer than the
//! skin at build time, grouped by i (compressed rows `start`), with the periodic image
//! shift of j frozen until the next build (positions are wrapped into the box only at a
//! build). It stays valid while no particle has moved more than half the skin since the
//! build. A reverse index (pairs where a particle is j, in increasing pair order) lets
//! each particle gather its contact forces in a fixed order, so the force sums do not
//! depend on the number of threads.
//!
//! A rebuild reuses the buffers of the previous list (they only grow), and carries the
//! tangential history of the pairs that survive. On more than one thread its rows are
//! found in parallel, over fixed chunks of [`CHUNK`] particles each writing its own
//! part, and the parts put end to end in chunk order (on one thread, one part that
//! becomes the list): the same list on any number of threads, and the build no longer
//! runs on one thread while the other waits (it was 15 % of a step at the peer's time
//! step).
//!
//! # The skin follows the motion
//!
//! A skin fixed in diameters is rebuilt every few steps at the large time steps users
//! run (in the peer's bedload case, `cases/maurin2015/peer_bedload_1165.toml`, a grain
//! at 1 m/s crosses half of 0.1 d in 7 steps of 0.22 contact times), and a skin wide
//! enough for the fastest grains lists several times the pairs of a bed at rest. So the skin adapts at every rebuild caused by motion: with n steps
//! since the previous build, the skin is multiplied by sqrt(N / n) (N =
//! [`TARGET_STEPS`]; the factor kept within [1/2, 2], the geometric mean of the old
//! skin and the one that would have lasted N steps at the same speed), and kept between
//! the scene's `skin` (the smallest) and [`MAX_SKIN_DIAMETERS`] diameters (less in a box
//! so small that a larger skin would meet two images of a particle). The criterion
//! itself does not change: a rebuild as soon as any mobile particle moved more than half
//! the current skin, so no contact is ever missed whatever the skin, and the policy
//! only trades pairs against rebuilds. It depends on step counts only, never on timings,
//! so a run stays the same for a seed on any number of threads, and it is saved with the
//! list in a checkpoint.

use rayon::prelude::*;

use super::chunks::{chunks_per_task, CHUNK};
use super::particles::{Box3, Particles, Place};

/// Pair list with history.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct NeighbourList {
    /// first particle of each pair
    pub i: Vec<u32>,
    /// second particle of each pair
    pub j: Vec<u32>,
    /// periodic image shift added to x_j, y_j, z_j
    pub shift: Vec<[f64; 3]>,
    /// sqrt of the pair's effective mass
    pub sqrt_m: Vec<f64>,
    /// effective radius R_i R_j / (R_i + R_j)
    pub r_eff: Vec<f64>,
    /// tangential spring displacement (contact history), zero when not in contact
    pub hist: Vec<[f64; 3]>,
    /// pairs of particle p as i: `start[p]..start[p + 1]`
    pub start: Vec<usize>,
    /// pairs of particle p as j: `rev[rev_start[p]..rev_start[p + 1]]`
    pub rev_start: Vec<usize>,
    /// pair indices, grouped by j
    pub rev: Vec<u32>,
    /// positions at the last build
    pub x0: Vec<[f64; 3]>,
    /// surface distance below which pairs are listed (m), adapted at each rebuild
    pub skin: f64,
    /// the smallest skin (m): the scene's `skin`
    pub skin_min: f64,
    /// number of builds
    pub builds: usize,
    /// steps since the last build ([`NeighbourList::tick`])
    pub steps_since: u64,
    // work buffers, refilled by every build: not part of a checkpoint
    #[serde(skip)]
    old_i_start: Vec<usize>,
    #[serde(skip)]
    old_j: Vec<u32>,
    #[serde(skip)]
    old_hist: Vec<[f64; 3]>,
    #[serde(skip)]
    cell_start: Vec<usize>,
    #[serde(skip)]
    cell_items: Vec<u32>,
    #[serde(skip)]
    cell_of: Vec<u32>,
    #[serde(skip)]
    fill: Vec<usize>,
    /// the wrapped positions and radii, as records for the candidate loop
    #[serde(skip)]
    place: Vec<Place>,
    /// the rows of each chunk of particles, before they are put end to end
    #[serde(skip)]
    parts: Vec<Rows>,
}

/// The rows of a chunk of particles: the pairs in the order of [`NeighbourList`], and the
/// end of each particle's row.
#[derive(Clone, Debug, Default)]
struct Rows {
    i: Vec<u32>,
    j: Vec<u32>,
    shift: Vec<[f64; 3]>,
    sqrt_m: Vec<f64>,
    r_eff: Vec<f64>,
    hist: Vec<[f64; 3]>,
    ends: Vec<usize>,
}

impl Rows {
    fn clear(&mut self) {
        self.i.clear();
        self.j.clear();
        self.shift.clear();
        self.sqrt_m.clear();
        self.r_eff.clear();
        self.hist.clear();
        self.ends.clear();
    }
}

/// Steps between rebuilds the skin is adapted to. On the peer's bedload case at 0.22
/// contact times per step, 15, 25 and 40 steps cost about the same CPU per step, 25 the
/// least (a skin of 0.33 d there, 1.5 times the pairs of 0.1 d; docs/performance.md
/// gives the case's throughput).
pub const TARGET_STEPS: f64 = 25.0;
/// Largest adapted skin, in diameters of the largest particle.
pub const MAX_SKIN_DIAMETERS: f64 = 1.0;

/// Most cells of the neighbour grid per particle (see [`NeighbourList::build`]).
pub const MAX_CELLS_PER_PARTICLE: usize = 8;
/// Cells the neighbour grid may always have, whatever the particle count.
pub const MIN_CELL_CAP: usize = 1 << 16;

/// Cell-list geometry along one axis.
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: f64,
    size: f64,
    n: usize,
    periodic: bool,
}

impl Axis {
    #[inline]
    fn index(&self, v: f64) -> usize {
        // truncation is the floor of the positive values: no libm call per particle
        let k = (v - self.lo) / self.size;
        if k > 0.0 {
            (k as usize).min(self.n - 1)
        } else {
            0
        }
    }
    /// distinct neighbour offsets, so that a short periodic axis is not visited twice
    fn offsets(&self) -> &'static [isize] {
        if !self.periodic || self.n >= 3 {
            &[-1, 0, 1]
        } else if self.n == 2 {
            &[0, 1]
        } else {
            &[0]
        }
    }
    /// The cell `o` (-1, 0 or 1) from cell `k`; wrapped by comparison on a periodic
    /// axis (the `rem_euclid` it replaces was an integer division per visited cell,
    /// about a tenth of a build)
    #[inline]
    fn neighbour(&self, k: usize, o: isize) -> Option<usize> {
        let m = k as isize + o;
        let n = self.n as isize;
        if self.periodic {
            Some(if m < 0 {
                m + n
            } else if m >= n {
                m - n
            } else {
                m
            } as usize)
        } else if m < 0 || m >= n {
            None
        } else {
            Some(m as usize)
        }
    }
}

/// What the rows of a build read: the particles, the cell list and the previous list.
struct Grid<'a> {
    place: &'a [Place],
    inv_mass: &'a [f64],
    cell_items: &'a [u32],
    cell_start: &'a [usize],
    /// empty when there is no previous list to carry histories from
    old_i_start: &'a [usize],
    old_j: &'a [u32],
    old_hist: &'a [[f64; 3]],
    skin: f64,
    half: [f64; 3],
    period: [f64; 3],
    axes: [Axis; 3],
}

impl Grid<'_> {
    /// The rows of the particles `range` into `out`. The slices are taken into locals
    /// first: read through the structure, their addresses would be reloaded after every
    /// push into `out`.
    fn rows(&self, range: std::ops::Range<usize>, out: &mut Rows) {
        let Grid { place, inv_mass, cell_items, cell_start, old_i_start, old_j, old_hist, .. } = *self;
        let (skin, half, period, axes) = (self.skin, self.half, self.period, self.axes);
        let had_old = !old_i_start.is_empty();
        for a in range {
            let [xa, ya, za, ra] = place[a].0;
            let fixed_a = inv_mass[a] == 0.0;
            let ix = axes[0].index(xa);
            let iy = axes[1].index(ya);
            let iz = axes[2].index(za);
            let old = if had_old { old_i_start[a]..old_i_start[a + 1] } else { 0..0 };
            for &oz in axes[2].offsets() {
                let Some(cz) = axes[2].neighbour(iz, oz) else { continue };
                for &oy in axes[1].offsets() {
                    let Some(cy) = axes[1].neighbour(iy, oy) else { continue };
                    for &ox in axes[0].offsets() {
                        let Some(cx) = axes[0].neighbour(ix, ox) else { continue };
                        let c = (cz * axes[1].n + cy) * axes[0].n + cx;
                        // a cell lists its particles in increasing index order: the
                        // partners b > a are a suffix, found without a branch per
                        // candidate (half of them, unpredictable, were skipped one by one)
                        let items = &cell_items[cell_start[c]..cell_start[c + 1]];
                        let later = items.partition_point(|&b| b as usize <= a);
                        for &b in &items[later..] {
                            let b = b as usize;
                            if fixed_a && inv_mass[b] == 0.0 {
                                continue;
                            }
                            let [xb, yb, zb, rb] = place[b].0;
                            let mut d = [xb - xa, yb - ya, zb - za];
                            let mut s = [0.0; 3];
                            for k in 0..3 {
                                s[k] = if d[k] > half[k] {
                                    -period[k]
                                } else if d[k] < -half[k] {
                                    period[k]
                                } else {
                                    0.0
                                };
                                d[k] += s[k];
                            }
                            let reach = ra + rb + skin;
                            if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= reach * reach {
                                continue;
                            }
                            let h = old_j[old.clone()]
                                .iter()
                                .position(|&oj| oj as usize == b)
                                .map_or([0.0; 3], |q| old_hist[old.start + q]);
                            let inv_m = inv_mass[a] + inv_mass[b];
                            out.i.push(a as u32);
                            out.j.push(b as u32);
                            out.shift.push(s);
                            out.sqrt_m.push((1.0 / inv_m).sqrt());
                            out.r_eff.push(ra * rb / (ra + rb));
                            out.hist.push(h);
                        }
                    }
                }
            }
            out.ends.push(out.i.len());
        }
    }
}

impl NeighbourList {
    /// An empty list with surface-distance skin `skin` (m), the smallest the list adapts
    /// to.
    pub fn new(skin: f64) -> Self {
        Self { skin, skin_min: skin, ..Default::default() }
    }

    /// Count one step of the particles since the last build.
    #[inline]
    pub fn tick(&mut self) {
        self.steps_since += 1;
    }

    /// The skin for the next build after `n` steps on the current one (see the module
    /// documentation), between the smallest skin and `largest`.
    pub fn adapted_skin(&self, n: u64, largest: f64) -> f64 {
        let factor = (TARGET_STEPS / n.max(1) as f64).sqrt().clamp(0.5, 2.0);
        (self.skin * factor).min(largest).max(self.skin_min)
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// Whether the list is empty.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Forget the contact history (after particles were renumbered).
    pub fn forget(&mut self) {
        self.start.clear();
        self.x0.clear();
    }

    /// Whether a mobile particle moved more than half the skin since the last build.
    pub fn needs_rebuild(&self, p: &Particles) -> bool {
        if self.x0.len() != p.len() {
            return true;
        }
        let lim = 0.25 * self.skin * self.skin;
        (0..p.n_mobile).any(|k| {
            let a = self.x0[k];
            (p.x[k] - a[0]).powi(2) + (p.y[k] - a[1]).powi(2) + (p.z[k] - a[2]).powi(2) > lim
        })
    }

    /// Wrap positions into the periodic box and rebuild the list, keeping the history of
    /// surviving pairs.
    pub fn build(&mut self, p: &mut Particles, bx: &Box3) {
        let n = p.len();
        let rmax = p.radius.iter().fold(0.0f64, |a, &r| a.max(r));
        // a rebuild caused by motion (not the first build, nor one after a change of
        // the particles) adapts the skin; the minimum image bounds it: the list must not
        // hold two images of a pair, so the cut-off stays below half the shortest period
        if self.x0.len() == n && self.steps_since > 0 {
            let period = (0..3).filter(|&k| bx.periodic[k]).map(|k| bx.length[k]).fold(f64::INFINITY, f64::min);
            let largest = (MAX_SKIN_DIAMETERS * 2.0 * rmax).min(0.99 * (0.5 * period - 2.0 * rmax));
            self.skin = self.adapted_skin(self.steps_since, largest);
        }
        self.steps_since = 0;
        for (axis, v) in [&mut p.x, &mut p.y, &mut p.z].into_iter().enumerate() {
            if bx.periodic[axis] {
                let l = bx.length[axis];
                for c in v.iter_mut() {
                    *c -= l * (*c / l).floor();
                    if *c >= l {
                        *c -= l;
                    }
                }
            }
        }
        // keep the old list for the history transfer
        std::mem::swap(&mut self.j, &mut self.old_j);
        std::mem::swap(&mut self.hist, &mut self.old_hist);
        std::mem::swap(&mut self.start, &mut self.old_i_start);
        let had_old = self.old_i_start.len() == n + 1;

        let cut = 2.0 * rmax + self.skin;
        let mut axes = [Axis { lo: 0.0, size: 1.0, n: 1, periodic: false }; 3];
        for (axis, v) in [&p.x, &p.y, &p.z].into_iter().enumerate() {
            if bx.periodic[axis] {
                let l = bx.length[axis];
                let m = ((l / cut).floor() as usize).max(1);
                axes[axis] = Axis { lo: 0.0, size: l / m as f64, n: m, periodic: true };
            } else {
                let lo = v.iter().fold(f64::INFINITY, |a, &c| a.min(c));
                let hi = v.iter().fold(f64::NEG_INFINITY, |a, &c| a.max(c));
                let (lo, hi) = if n == 0 { (0.0, 0.0) } else { (lo, hi) };
                // clamped as a float before the cast: a particle flung to infinity (caught by
                // the next check of the state) must not wrap the count to zero cells
                let m = ((hi - lo) / cut).floor().clamp(0.0, ((1 << 20) - 1) as f64) as usize + 1;
                axes[axis] = Axis { lo, size: cut, n: m, periodic: false };
            }
        }
        // bound the grid by the particle count: a box much larger than its particles (a
        // few grains in a tall or wide box, one grain flung far away) would otherwise ask
        // for cells by the billion. Coarser cells list the same pairs (a cell only has to
        // be at least the cut-off), so this costs speed in such boxes, never correctness;
        // the bound is far above the cells of a bed (about one per particle), whose grid
        // (and with it the pair order) it leaves unchanged.
        let cap = (MAX_CELLS_PER_PARTICLE * n).max(MIN_CELL_CAP);
        while axes.iter().map(|a| a.n).product::<usize>() > cap {
            let Some(a) = axes.iter_mut().max_by_key(|a| a.n) else { break };
            if a.periodic {
                let l = a.size * a.n as f64;
                a.n = a.n.div_ceil(2);
                a.size = l / a.n as f64;
            } else {
                // n cells of `size` cover the particles' span; half as many of twice the size
                // still do
                a.size *= 2.0;
                a.n = a.n.div_ceil(2);
            }
        }
        let ncell = axes[0].n * axes[1].n * axes[2].n;
        let cell_id = |ix: usize, iy: usize, iz: usize| (iz * axes[1].n + iy) * axes[0].n + ix;
        self.cell_of.clear();
        self.cell_of.extend(
            (0..n).map(|k| cell_id(axes[0].index(p.x[k]), axes[1].index(p.y[k]), axes[2].index(p.z[k])) as u32),
        );
        self.cell_start.clear();
        self.cell_start.resize(ncell + 1, 0);
        for &c in &self.cell_of {
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..ncell {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.cell_items.clear();
        self.cell_items.resize(n, 0);
        {
            // stable fill: particles of a cell in increasing index order
            let fill = &mut self.fill;
            fill.clear();
            fill.extend_from_slice(&self.cell_start);
            for (k, &c) in self.cell_of.iter().enumerate() {
                self.cell_items[fill[c as usize]] = k as u32;
                fill[c as usize] += 1;
            }
        }

        // the minimum image of a difference of wrapped coordinates, |d| < L, by
        // comparison (the same shift as Box3::image_shift without its libm round)
        let (mut half, mut period) = ([f64::INFINITY; 3], [0.0; 3]);
        for k in 0..3 {
            if bx.periodic[k] {
                (half[k], period[k]) = (0.5 * bx.length[k], bx.length[k]);
            }
        }
        // the rows of fixed chunks of particles in parallel, each into its own part, then
        // the parts end to end: the same pairs in the same order on any number of threads
        p.places(&mut self.place);
        let grid = Grid {
            place: &self.place,
            inv_mass: &p.inv_mass,
            cell_items: &self.cell_items,
            cell_start: &self.cell_start,
            old_i_start: if had_old { &self.old_i_start } else { &[] },
            old_j: &self.old_j,
            old_hist: &self.old_hist,
            skin: self.skin,
            half,
            period,
            axes,
        };
        // one part on one thread (no copy: the part becomes the list), chunks of CHUNK
        // particles otherwise; the list is the same whatever the parts
        let len = if rayon::current_num_threads() > 1 { CHUNK } else { n.max(1) };
        let parts = n.div_ceil(len).max(1);
        if self.parts.len() < parts {
            self.parts.resize_with(parts, Rows::default);
        }
        self.parts[..parts].par_iter_mut().enumerate().with_max_len(chunks_per_task()).for_each(|(c, part)| {
            part.clear();
            grid.rows(c * len..((c + 1) * len).min(n), part);
        });
        // the first part's buffers become the list's, the others are appended
        let first = &mut self.parts[0];
        std::mem::swap(&mut self.i, &mut first.i);
        std::mem::swap(&mut self.j, &mut first.j);
        std::mem::swap(&mut self.shift, &mut first.shift);
        std::mem::swap(&mut self.sqrt_m, &mut first.sqrt_m);
        std::mem::swap(&mut self.r_eff, &mut first.r_eff);
        std::mem::swap(&mut self.hist, &mut first.hist);
        self.start.clear();
        self.start.push(0);
        self.start.extend_from_slice(&first.ends);
        for part in &self.parts[1..parts] {
            let base = self.i.len();
            self.start.extend(part.ends.iter().map(|e| base + e));
            self.i.extend_from_slice(&part.i);
            self.j.extend_from_slice(&part.j);
            self.shift.extend_from_slice(&part.shift);
            self.sqrt_m.extend_from_slice(&part.sqrt_m);
            self.r_eff.extend_from_slice(&part.r_eff);
            self.hist.extend_from_slice(&part.hist);
        }
        // reverse index
        self.rev_start.clear();
        self.rev_start.resize(n + 1, 0);
        for &b in &self.j {
            self.rev_start[b as usize + 1] += 1;
        }
        for k in 0..n {
            self.rev_start[k + 1] += self.rev_start[k];
        }
        self.rev.clear();
        self.rev.resize(self.j.len(), 0);
        {
            let fill = &mut self.fill;
            fill.clear();
            fill.extend_from_slice(&self.rev_start);
            for (q, &b) in self.j.iter().enumerate() {
                self.rev[fill[b as usize]] = q as u32;
                fill[b as usize] += 1;
            }
        }
        self.x0.clear();
        self.x0.extend((0..n).map(|k| [p.x[k], p.y[k], p.z[k]]));
        self.builds += 1;
    }
}

/// Every pair (a < b) of `p` whose surfaces are closer than `gap` (0: in contact), by
/// brute force over all pairs and their minimum images: what a list must hold.
#[cfg(test)]
pub(crate) fn pairs_within(p: &Particles, bx: &Box3, gap: f64) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            let mut d2 = 0.0;
            for (k, c) in [&p.x, &p.y, &p.z].into_iter().enumerate() {
                let d = c[b] - c[a];
                let d = d + bx.image_shift(k, d);
                d2 += d * d;
            }
            if d2 < (p.radius[a] + p.radius[b] + gap).powi(2) {
                out.push((a, b));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests;
