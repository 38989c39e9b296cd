//! Initial particles, box and walls of a scene; the rough bottom of fixed particles.
//!
//! Rough bottom (Maurin et al. 2015 section IV: "the random fixed bottom is generated from
//! a gravity deposition, fixing all the particles contained in a slice of height d at a
//! given elevation in the granular bed"): the bed is deposited with `2 + rough_layer`
//! extra diameters of particles on a flat wall; after the deposition the particles are
//! ranked by height, the lowest two diameters' worth are removed (they carry the
//! crystalline layering of the flat wall), the next `rough_layer` diameters' worth are
//! fixed, and everything is lowered so that the lowest fixed sphere touches z = 0. The
//! flat wall stays at z = 0 as a backstop. Every random draw comes from streams derived
//! from the scene seed.
//!
//! Frey bottoms (Maurin et al. 2015 section III A-B): `bead_row` puts fixed beads of
//! diameter d side by side, one per diameter along x and across, `half_cylinders` puts
//! cylinders of diameter d with axes across the channel ([`crate::lagrangian::engine::cylinders`]); both at
//! z = d plus an elevation drawn uniformly from (k - 5.5) d / 12, k = 0..11 (the paper's
//! -2.75 to 2.75 mm in steps of 0.5 mm for d = 6 mm), the column starting at their mean
//! elevation d. The bed is released above them (from 2 d) and deposited; nothing is
//! removed or fixed after the deposition.

use rand::Rng as _;
use rand_distr::{Distribution, StandardNormal};
use saltus_core::rng::stream;
use saltus_core::scene::FREY_LEVELS;
use saltus_core::Error;

use super::config::{Bottom, Config, FluidMode, Initial};
use crate::lagrangian::engine::cylinders::HalfCylinders;
use crate::lagrangian::engine::particles::{Box3, Particles};
use crate::lagrangian::engine::walls::Wall;
use saltus_core::grain::sphere_volume;

/// Stream numbers of the set-up draws, far from the per-particle streams.
const SETUP_STREAM: u64 = u64::MAX - 16;
/// Stream of the elevations of a Frey bottom (its own, so the lattice keeps its draws).
const FREY_STREAM: u64 = u64::MAX - 17;

/// Physical data the set-up needs.
#[derive(Clone, Copy, Debug)]
pub struct Material {
    /// diameter (m)
    pub d: f64,
    /// particle density (kg/m^3)
    pub rho_p: f64,
}

/// The periodic box of the scene.
pub fn make_box(cfg: &Config) -> Box3 {
    let dm = &cfg.domain;
    Box3 {
        length: [
            dm.length,
            dm.width,
            if cfg.settings.numerics.bottom == Bottom::Periodic { cfg.settings.numerics.height } else { 0.0 },
        ],
        periodic: [true, !cfg.settings.numerics.side_walls, cfg.settings.numerics.bottom == Bottom::Periodic],
    }
}

/// The flat walls of the scene.
pub fn make_walls(cfg: &Config) -> Vec<Wall> {
    let dm = &cfg.domain;
    let mut w = Vec::new();
    if matches!(cfg.settings.numerics.bottom, Bottom::Rough | Bottom::Wall | Bottom::BeadRow | Bottom::HalfCylinders) {
        w.push(Wall { axis: 2, position: 0.0, sign: 1.0 });
    }
    if cfg.settings.numerics.side_walls {
        w.push(Wall { axis: 1, position: 0.0, sign: 1.0 });
        w.push(Wall { axis: 1, position: dm.width, sign: -1.0 });
    }
    w
}

/// Number of particles filling `height` of the box at `phi`.
fn count(cfg: &Config, m: &Material, height: f64, phi: f64) -> usize {
    (phi * cfg.domain.length * cfg.domain.width * height / sphere_volume(m.d)).round() as usize
}

/// Mobile particles to deposit (bed), including the extra ones that become the rough
/// layer or are removed under it; and how many of them are removed and fixed.
pub fn bed_counts(cfg: &Config, m: &Material) -> (usize, usize, usize) {
    let dm = &cfg.domain;
    let mobile = cfg.settings.numerics.particles.unwrap_or_else(|| count(cfg, m, dm.bed_height, dm.bed_phi));
    if cfg.settings.numerics.bottom == Bottom::Rough {
        let removed = count(cfg, m, 2.0 * m.d, dm.bed_phi);
        let fixed = count(cfg, m, cfg.settings.numerics.rough_layer * m.d, dm.bed_phi).max(1);
        (mobile + removed + fixed, removed, fixed)
    } else {
        (mobile, 0, 0)
    }
}

/// `n` elevations of a Frey bottom above z = 0 (m): d + (k - 5.5) d / 12, k drawn
/// uniformly in 0..12 (Maurin et al. 2015 section III A), from the scene seed.
pub fn frey_elevations(n: usize, d: f64, seed: u64) -> Vec<f64> {
    let mut rng = stream(seed, FREY_STREAM);
    let levels = FREY_LEVELS as f64;
    (0..n)
        .map(|_| {
            let k = rng.gen_range(0..FREY_LEVELS) as f64;
            d + (k - 0.5 * (levels - 1.0)) * d / levels
        })
        .collect()
}

/// Elements of a Frey bottom along a side of `length` (m): one per diameter, at least one.
fn frey_count(length: f64, d: f64) -> usize {
    ((length / d).floor() as usize).max(1)
}

/// The half-cylinders of `bottom = "half_cylinders"`, None for other bottoms.
pub fn half_cylinders(cfg: &Config, m: &Material, seed: u64) -> Option<HalfCylinders> {
    (cfg.settings.numerics.bottom == Bottom::HalfCylinders).then(|| {
        let n = frey_count(cfg.domain.length, m.d);
        HalfCylinders { radius: 0.5 * m.d, spacing: cfg.domain.length / n as f64, z: frey_elevations(n, m.d, seed) }
    })
}

/// Push the fixed beads of `bottom = "bead_row"`: one per diameter along x and across
/// (centred between side walls), at the Frey elevations.
fn push_bead_row(p: &mut Particles, cfg: &Config, m: &Material, seed: u64) {
    let dm = &cfg.domain;
    let (nx, ny) = (frey_count(dm.length, m.d), frey_count(dm.width, m.d));
    let (sx, sy) = (dm.length / nx as f64, dm.width / ny as f64);
    let z = frey_elevations(nx * ny, m.d, seed);
    for iy in 0..ny {
        for ix in 0..nx {
            let pos = [(ix as f64 + 0.5) * sx, (iy as f64 + 0.5) * sy, z[iy * nx + ix]];
            p.push(pos, [0.0; 3], [0.0; 3], 0.5 * m.d, m.rho_p, true);
        }
    }
}

/// Initial particles of the scene (before any deposition).
pub fn initial_particles(cfg: &Config, m: &Material, seed: u64, file: &str) -> Result<Particles, Error> {
    let dm = &cfg.domain;
    let r = 0.5 * m.d;
    let mut rng = stream(seed, SETUP_STREAM);
    let mut p = Particles::default();
    match cfg.settings.numerics.initial {
        Initial::List => {
            for s in cfg.settings.numerics.particle_list.iter().filter(|s| !s.fixed) {
                p.push(s.position, s.velocity, s.angular_velocity, r, m.rho_p, false);
            }
            if cfg.settings.numerics.bottom == Bottom::BeadRow {
                push_bead_row(&mut p, cfg, m, seed);
            }
            for s in cfg.settings.numerics.particle_list.iter().filter(|s| s.fixed) {
                p.push(s.position, s.velocity, s.angular_velocity, r, m.rho_p, true);
            }
        }
        Initial::Bed => {
            let (n, _, _) = bed_counts(cfg, m);
            // loose lattice, jittered, with small random velocities to break the symmetry
            let a = 1.1 * m.d;
            let nx = ((dm.length / a).floor() as usize).max(1);
            let (y0, ny) = if cfg.settings.numerics.side_walls {
                (r, (((dm.width - m.d) / a).floor() as usize + 1).max(1))
            } else {
                (0.0, ((dm.width / a).floor() as usize).max(1))
            };
            let (sx, sy) =
                (dm.length / nx as f64, if cfg.settings.numerics.side_walls { a } else { dm.width / ny as f64 });
            let per_layer = nx * ny;
            let jitter = 0.02 * m.d;
            // released above a Frey bottom, whose tops reach 1.96 d
            let floor = if cfg.settings.numerics.bottom.is_frey() { 2.0 * m.d } else { 0.0 };
            for k in 0..n {
                let (layer, in_layer) = (k / per_layer, k % per_layer);
                let (ix, iy) = (in_layer % nx, in_layer / nx);
                let mut pos = [
                    (ix as f64 + 0.5) * sx + jitter * (2.0 * rng.gen::<f64>() - 1.0),
                    y0 + if cfg.settings.numerics.side_walls { iy as f64 * sy } else { (iy as f64 + 0.5) * sy },
                    floor + r + 0.05 * m.d + layer as f64 * a,
                ];
                if !cfg.settings.numerics.side_walls {
                    pos[1] += jitter * (2.0 * rng.gen::<f64>() - 1.0);
                }
                let v = [0.0, 0.0, -0.01 * rng.gen::<f64>()];
                // drawn only when asked, so that a monodisperse bed keeps its random stream
                let s = cfg.settings.numerics.size_dispersion;
                let radius = if s > 0.0 { r * (1.0 + s * (2.0 * rng.gen::<f64>() - 1.0)) } else { r };
                p.push(pos, v, [0.0; 3], radius, m.rho_p, false);
            }
            if cfg.settings.numerics.bottom == Bottom::BeadRow {
                push_bead_row(&mut p, cfg, m, seed);
            }
        }
        Initial::Gas => {
            let n = cfg
                .settings
                .numerics
                .particles
                .unwrap_or_else(|| count(cfg, m, cfg.settings.numerics.height, cfg.settings.numerics.gas_phi));
            let (lx, ly, lz) = (dm.length, dm.width, cfg.settings.numerics.height);
            let a0 = (lx * ly * lz / n.max(1) as f64).cbrt();
            let mut dims = [(lx / a0).ceil() as usize, (ly / a0).ceil() as usize, (lz / a0).ceil() as usize];
            while dims[0] * dims[1] * dims[2] < n {
                dims[2] += 1;
            }
            let sp = [lx / dims[0] as f64, ly / dims[1] as f64, lz / dims[2] as f64];
            if sp.iter().any(|&s| s <= m.d * 1.0001) {
                return Err(Error::Invalid(format!(
                    "{file}: key `solver.lagrangian.particles`: {n} particles do not fit on a lattice in the box; lower particles or gas_phi, or enlarge the box"
                )));
            }
            let sd = cfg.settings.numerics.gas_temperature.sqrt();
            let mut vel = Vec::with_capacity(n);
            for _ in 0..n {
                let mut normal = || -> f64 { StandardNormal.sample(&mut rng) };
                let v: [f64; 3] = [sd * normal(), sd * normal(), sd * normal()];
                vel.push(v);
            }
            // zero total momentum and exactly the asked temperature
            let nf = n as f64;
            let mean: Vec<f64> = (0..3).map(|c| vel.iter().map(|v| v[c]).sum::<f64>() / nf).collect();
            let mut t = 0.0;
            for v in vel.iter_mut() {
                for c in 0..3 {
                    v[c] -= mean[c];
                    t += v[c] * v[c];
                }
            }
            let scale = if t > 0.0 { (cfg.settings.numerics.gas_temperature * 3.0 * nf / t).sqrt() } else { 0.0 };
            for (k, v) in vel.iter().enumerate() {
                let (ix, iy, iz) = (k % dims[0], (k / dims[0]) % dims[1], k / (dims[0] * dims[1]));
                let pos = [(ix as f64 + 0.5) * sp[0], (iy as f64 + 0.5) * sp[1], (iz as f64 + 0.5) * sp[2]];
                p.push(pos, [v[0] * scale, v[1] * scale, v[2] * scale], [0.0; 3], r, m.rho_p, false);
            }
        }
    }
    Ok(p)
}

/// Turn a deposited bed into the rough bottom: rank by height, remove the lowest
/// `removed`, fix the next `fixed`, lower everything so the lowest fixed sphere touches
/// z = 0. Returns the new particle set (mobile first, at rest, then fixed).
pub fn fix_rough_layer(p: &Particles, removed: usize, fixed: usize, rho_p: f64) -> Particles {
    let mut order: Vec<usize> = (0..p.n_mobile).collect();
    order.sort_by(|&a, &b| p.z[a].total_cmp(&p.z[b]).then(a.cmp(&b)));
    let fixed_set = &order[removed.min(order.len())..(removed + fixed).min(order.len())];
    let lowest = fixed_set.iter().map(|&k| p.z[k] - p.radius[k]).fold(f64::INFINITY, f64::min);
    let drop = if lowest.is_finite() { lowest } else { 0.0 };
    let mut keep_mobile: Vec<usize> = order[(removed + fixed).min(order.len())..].to_vec();
    keep_mobile.sort_unstable();
    let mut fixed_sorted = fixed_set.to_vec();
    fixed_sorted.sort_unstable();
    let mut out = Particles::default();
    for (&k, is_fixed) in keep_mobile.iter().map(|k| (k, false)).chain(fixed_sorted.iter().map(|k| (k, true))) {
        out.push([p.x[k], p.y[k], p.z[k] - drop], [0.0; 3], [0.0; 3], p.radius[k], rho_p, is_fixed);
    }
    out
}

/// Body acceleration of mobile particles (m/s^2): gravity along the slope and
/// bed-normal, buoyancy in the bed-normal direction only (Maurin 2015 section II C 2: the
/// buoyant weight is applied in the vertical direction; the free surface is parallel to
/// the bed, so the fluid pressure gradient has no streamwise part), and the imposed
/// pressure gradient G felt by the particle volume.
pub fn body_acceleration(cfg: &Config, g: f64, slope: f64, rho_f: f64, rho_p: f64, grad: f64) -> [f64; 3] {
    let cos = (1.0 - slope * slope).max(0.0).sqrt();
    let wet = cfg.settings.numerics.fluid != FluidMode::Off;
    let buoy = if wet { rho_f / rho_p } else { 0.0 };
    let gx = g * slope + if wet { grad / rho_p } else { 0.0 };
    [gx, 0.0, -g * cos * (1.0 - buoy)]
}
