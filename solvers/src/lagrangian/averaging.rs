//! Slice averaging of the particles onto the fluid cells (Maurin et al. 2015 eqs 6-8 and
//! appendix eq A1) and the implicit drag coefficient of eq 18.
//!
//! With the cuboid weighting function of eq 8 over the whole periodic cell and one fluid
//! cell in z, the volume fraction of cell c is phi_c = sum_p V_pc / (A dz) and the
//! solid-phase average of a particle quantity g is `<g>_c = sum_p V_pc g_p / sum_p V_pc`
//! (eq A1), with V_pc the exact volume of the slice of sphere p inside cell c (Hill et al.;
//! from the spherical-cap volume pi s^2 (3R - s) / 3).
//!
//! Momentum exchange (eqs 14, 17-18): n <f_Dx> = sum_p (V_pc / V_p) F_Dx,p / (A dz), and
//! beta = n <f_Dx> / (u_f - <v_x>), so that the fluid loses exactly the momentum the
//! particles gain. Where that quotient is not a usable coefficient (|u_f - <v_x>| below
//! 1e-9 m/s, or a negative or non-finite quotient, which the stochastic fluctuations can
//! produce in a nearly static bed), beta falls back to the mean linear coefficient
//! sum_p (V_pc / V_p) k_p / (A dz) (the same value when every particle of the cell has
//! the same slip), and the quotient is capped at 10 times that coefficient so that a
//! vanishing denominator never pins the fluid to the particles.

use super::particles::Particles;

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

/// Per-cell sums of one averaging pass.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct CellSums {
    /// sum of slice volumes (m^3)
    pub vol: Vec<f64>,
    /// sums of slice volume times velocity components (m^4/s)
    pub v: [Vec<f64>; 3],
    /// sums of slice volume times velocity products xx, yy, zz, xz (m^5/s^2)
    pub vv: [Vec<f64>; 4],
    /// sum of (V_pc / V_p) F_Dx,p (N)
    pub drag: Vec<f64>,
    /// sum of (V_pc / V_p) k_p (kg/s)
    pub coef: Vec<f64>,
}

impl CellSums {
    /// Zeroed sums over `n` cells.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self { vol: z(), v: [z(), z(), z()], vv: [z(), z(), z(), z()], drag: z(), coef: z() }
    }

    /// Accumulate every particle (mobile and fixed; fixed ones have zero velocity) on a
    /// uniform grid of `n` cells of height `dz` from z = `base`, with the drag
    /// coefficients `k` and streamwise slips `urx` of the last drag evaluation. Parts of
    /// spheres outside the column are dropped (their drag share too). Sequential, in
    /// particle order: bit-reproducible.
    pub fn accumulate(&mut self, p: &Particles, base: f64, dz: f64, k: &[f64], urx: &[f64]) {
        for v in [&mut self.vol, &mut self.drag, &mut self.coef]
            .into_iter()
            .chain(self.v.iter_mut())
            .chain(self.vv.iter_mut())
        {
            v.fill(0.0);
        }
        let n = self.vol.len();
        for a in 0..p.len() {
            let (zc, r) = (p.z[a] - base, p.radius[a]);
            let vp = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
            let (vx, vy, vz) = (p.vx[a], p.vy[a], p.vz[a]);
            let (fx, kp) = (k[a] * urx[a], k[a]);
            sphere_slices(zc, r, n, dz, |c, w| {
                self.vol[c] += w;
                self.v[0][c] += w * vx;
                self.v[1][c] += w * vy;
                self.v[2][c] += w * vz;
                self.vv[0][c] += w * vx * vx;
                self.vv[1][c] += w * vy * vy;
                self.vv[2][c] += w * vz * vz;
                self.vv[3][c] += w * vx * vz;
                let frac = w / vp;
                self.drag[c] += frac * fx;
                self.coef[c] += frac * kp;
            });
        }
    }

    /// Volume fraction, mean streamwise particle velocity and beta of eq 18 per cell for
    /// a slice volume `cell_volume` = A dz and the fluid velocity `u_f` per cell.
    pub fn coupling(&self, cell_volume: f64, u_f: &[f64], phi: &mut [f64], u_p: &mut [f64], beta: &mut [f64]) {
        for c in 0..self.vol.len() {
            phi[c] = self.vol[c] / cell_volume;
            u_p[c] = if self.vol[c] > 0.0 { self.v[0][c] / self.vol[c] } else { u_f[c] };
            let linear = self.coef[c] / cell_volume;
            let transfer = self.drag[c] / cell_volume;
            let slip = u_f[c] - u_p[c];
            let b = transfer / slip;
            beta[c] = if slip.abs() > 1e-9 && b.is_finite() && b >= 0.0 { b.min(10.0 * linear) } else { linear };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn slices_add_up_to_the_sphere(zc in 0.01f64..1.0, r in 1e-3f64..0.05, dz in 1e-4f64..0.05) {
            // whatever the cut, the slice volumes of a sphere inside the column sum to its volume
            let zc = zc.max(r);
            let n = ((zc + r) / dz).ceil() as usize + 2;
            let mut p = Particles::default();
            p.push([0.0, 0.0, zc], [1.0, 0.0, 0.0], [0.0; 3], r, 1000.0, false);
            let mut s = CellSums::new(n);
            s.accumulate(&p, 0.0, dz, &[0.0], &[0.0]);
            let total: f64 = s.vol.iter().sum();
            let v = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
            prop_assert!((total / v - 1.0).abs() < 1e-9);
            prop_assert!(s.vol.iter().all(|w| *w >= -1e-18));
        }

        #[test]
        fn beta_transfers_the_particle_drag(
            k in proptest::collection::vec(1e-4f64..1e-2, 1..20),
            slip in proptest::collection::vec(0.01f64..0.5, 20),
            z in proptest::collection::vec(0.004f64..0.05, 20),
        ) {
            // sum_c beta_c (u_f,c - <v>_c) A dz = sum_p F_x,p (Maurin eq 18) when every
            // quotient is used; particles move at 0, fluid at 1 m/s
            let (dz, area, n) = (0.002, 0.01, 30);
            let mut p = Particles::default();
            for (i, _) in k.iter().enumerate() {
                p.push([0.0, 0.0, z[i]], [0.0; 3], [0.0; 3], 0.003, 2500.0, false);
            }
            let urx: Vec<f64> = k.iter().enumerate().map(|(i, _)| slip[i]).collect();
            let mut s = CellSums::new(n);
            s.accumulate(&p, 0.0, dz, &k, &urx);
            let (mut phi, mut up, mut beta) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let uf = vec![1.0; n];
            s.coupling(area * dz, &uf, &mut phi, &mut up, &mut beta);
            let fluid: f64 = (0..n).map(|c| beta[c] * (uf[c] - up[c]) * area * dz).sum();
            let particles: f64 = k.iter().zip(&urx).map(|(k, u)| k * u).sum();
            // capped cells (beta > 10 x linear) cannot occur: slips are within a factor 50
            prop_assert!((fluid / particles - 1.0).abs() < 1e-9, "{} vs {}", fluid, particles);
        }
    }
}
