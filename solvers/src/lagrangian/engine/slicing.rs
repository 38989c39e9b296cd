//! The volume of a sphere inside horizontal slices: what the cell averages, the drag's
//! sphere-averaged fluid velocity and the granular fields weigh each particle by.

/// Volume of the part of a sphere of centre height `zc` and radius `r` below height `h`.
#[inline]
pub fn cap_volume(zc: f64, r: f64, h: f64) -> f64 {
    let s = (h - (zc - r)).clamp(0.0, 2.0 * r);
    std::f64::consts::PI * s * s * (3.0 * r - s) / 3.0
}

/// Call `f(c, w)` for every cell c of a uniform grid of `n` cells of height `dz` (from 0)
/// that the sphere of centre height `zc` and radius `r` (both from the grid's bottom)
/// crosses, with w the volume of the sphere inside the cell (exact, from
/// [`cap_volume`]); parts outside the grid are dropped.
#[inline]
pub fn sphere_slices(zc: f64, r: f64, n: usize, dz: f64, mut f: impl FnMut(usize, f64)) {
    let top = n as f64 * dz;
    if zc + r <= 0.0 || zc - r >= top {
        return;
    }
    let lo = (((zc - r) / dz).floor().max(0.0)) as usize;
    let hi = (((zc + r) / dz).floor() as usize).min(n - 1);
    let mut below = cap_volume(zc, r, lo as f64 * dz);
    for c in lo..=hi {
        let upto = cap_volume(zc, r, (c + 1) as f64 * dz);
        f(c, upto - below);
        below = upto;
    }
}
