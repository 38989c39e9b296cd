//! Slice averaging of the particles onto the fluid cells (Maurin et al. 2015 eqs 6-8 and
//! appendix eq A1) and the implicit momentum exchange of eqs 14, 17-18, in the form the
//! scene's `solver.lagrangian.drag_velocity` asks.
//!
//! With the cuboid weighting function of eq 8 over the whole periodic cell and one fluid
//! cell in z, the volume fraction of cell c is phi_c = sum_p V_pc / (A dz) and the
//! solid-phase average of a particle quantity g is `<g>_c = sum_p V_pc g_p / sum_p V_pc`
//! (eq A1), with V_pc the exact volume of the slice of sphere p inside cell c (Hill et al.;
//! from the spherical-cap volume pi s^2 (3R - s) / 3). w_pc = V_pc / V_p below.
//!
//! Each grain's drag is F_p = k_p u_r,p ([`super::drag`]), k_p >= 0 its own coefficient,
//! u_r,x = u_seen,p + u'_p - v_p with u'_p its fluctuation and u_seen,p the fluid velocity
//! its drag sees. The exchange depends on that velocity:
//!
//! * `"centre"` (Maurin eq 11: u_seen at the grain's centre, as the reference YADE code):
//!   n <f_Dx> = sum_p w_pc F_Dx,p / (A dz) and beta = n <f_Dx> / (u_f - <v_x>) (eq 18),
//!   so that the fluid loses the momentum the particles gain. Where that quotient is not
//!   a usable coefficient (|u_f - <v_x>| below 1e-9 m/s, or a negative or non-finite
//!   quotient, which the stochastic fluctuations or a bed moving with the fluid produce),
//!   beta falls back to the mean linear coefficient sum_p w_pc k_p / (A dz) (the same value
//!   when every particle of the cell has the same slip), and the quotient is capped at 10
//!   times that coefficient so that a vanishing denominator never pins the fluid to the
//!   particles. In those cells the fluid does not lose what the grains gain.
//! * `"sphere_average"`: u_seen,p = ubar_p = sum_c w_pc u_c, the fluid averaged over the
//!   grain with the slice volumes above ([`super::drag::FluidField::sphere_velocity`], at
//!   the drag evaluation of the fluid update). The fluid of cell c loses, at its new
//!   velocity u_c,
//!
//! ```text
//! sum_p w_pc (k_p (u_c - ubar_p) + F_x,p) = B_c u_c - M_c,
//! B_c = sum_p w_pc k_p,   M_c = sum_p w_pc (k_p ubar_p - F_x,p) = sum_p w_pc k_p (v_p - u'_p),
//! ```
//!
//!   handed to the column as beta_c = B_c / (A dz) (n <f_Dx> / (u_f - u_p) of eq 18 with
//!   the drag linearised grain by grain) and the exchange velocity M_c / B_c, the
//!   k-weighted grain velocity less the fluctuation. B_c >= 0 always, so nothing is
//!   refused. Summed over the cells the loss is sum_p F_x,p + sum_p k_p (ubar_p(u) -
//!   ubar_p(u_seen)): at the fluid the grains saw, exactly their drag, in any profile
//!   (ubar_p being the transpose of this averaging; with the velocity at the centre a
//!   sheared bed surface leaks). M_c holds no fluid velocity, so the exchange is implicit
//!   in u_c with the grains' own stiffness and carries no explicit fluid term.
//!
//! phi and the reported <v_x> are volume averages under both.

use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::engine::slicing::sphere_slices;
use saltus_core::grain::ball_volume;

/// Which exchange the third sum of [`CellSums`] holds, and how [`CellSums::coupling`]
/// reads it (module documentation).
#[derive(Clone, Copy, Debug)]
pub enum Seen<'a> {
    /// the drag saw the fluid at the grains' centres: sum_p w_pc F_Dx,p, Maurin's quotient
    Centre,
    /// the drag saw ubar_p, one per particle (at least as many as the particles): M_c
    SphereAverage(&'a [f64]),
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
    /// the exchange's grain term (N): sum_p w_pc F_Dx,p under `"centre"`, M_c = sum_p
    /// w_pc (k_p ubar_p - F_Dx,p) under `"sphere_average"` (same place in a checkpoint:
    /// rebuilt by [`Self::accumulate`] before any use)
    pub carried: Vec<f64>,
    /// B_c = sum of w_pc k_p (kg/s)
    pub coef: Vec<f64>,
    /// what `carried` holds: set by [`Self::accumulate`], not saved
    #[serde(skip)]
    exact: bool,
}

impl CellSums {
    /// Zeroed sums over `n` cells.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self { vol: z(), v: [z(), z(), z()], vv: [z(), z(), z(), z()], carried: z(), coef: z(), exact: false }
    }

    /// Accumulate every particle (mobile and fixed; fixed ones have zero velocity) on a
    /// uniform grid of `n` cells of height `dz` from z = `base`, with the drag
    /// coefficients `k` and streamwise slips `urx` of the last drag evaluation (each at
    /// least as long as `p`) and the velocity that drag saw, `seen`. Parts of spheres
    /// outside the column are dropped (their share of the exchange too). Sequential, in
    /// particle order: bit-reproducible.
    pub fn accumulate(&mut self, p: &Particles, base: f64, dz: f64, k: &[f64], urx: &[f64], seen: Seen<'_>) {
        for v in [&mut self.vol, &mut self.carried, &mut self.coef]
            .into_iter()
            .chain(self.v.iter_mut())
            .chain(self.vv.iter_mut())
        {
            v.fill(0.0);
        }
        self.exact = matches!(seen, Seen::SphereAverage(_));
        let n = self.vol.len();
        for a in 0..p.len() {
            let (zc, r) = (p.z[a] - base, p.radius[a]);
            let vp = ball_volume(r);
            let (vx, vy, vz) = (p.vx[a], p.vy[a], p.vz[a]);
            let kp = k[a];
            let carried = match seen {
                Seen::Centre => kp * urx[a],
                // k_p (ubar_p - u_r,x) = k_p (v_p - u'_p): no fluid velocity left in it
                Seen::SphereAverage(ubar) => kp * (ubar[a] - urx[a]),
            };
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
                self.carried[c] += frac * carried;
                self.coef[c] += frac * kp;
            });
        }
    }

    /// Volume fraction, beta and the particle velocity the column's exchange reads per
    /// cell, for a slice volume `cell_volume` = A dz and the fluid velocity `u_f` per cell,
    /// in the exchange of the last [`Self::accumulate`] (module documentation):
    /// `"centre"`: beta of eq 18 and the volume-averaged <v_x>; `"sphere_average"`: beta_c
    /// = B_c / (A dz) and M_c / B_c. A cell without drag gets the linear coefficient
    /// (`"centre"`) or beta 0 and `u_f` (`"sphere_average"`: no grain, or grains of k_p =
    /// 0, which the column then ignores).
    pub fn coupling(&self, cell_volume: f64, u_f: &[f64], phi: &mut [f64], u_p: &mut [f64], beta: &mut [f64]) {
        for c in 0..self.vol.len() {
            phi[c] = self.vol[c] / cell_volume;
            if self.exact {
                let (b, m) = (self.coef[c], self.carried[c]);
                let carried = m / b;
                // B_c > 0 makes M_c / B_c a k-weighted mean of v_p - u'_p, finite: the
                // test only sorts out the empty cells (0 / 0)
                if b > 0.0 && carried.is_finite() {
                    beta[c] = b / cell_volume;
                    u_p[c] = carried;
                } else {
                    beta[c] = 0.0;
                    u_p[c] = u_f[c];
                }
            } else {
                u_p[c] = if self.vol[c] > 0.0 { self.v[0][c] / self.vol[c] } else { u_f[c] };
                let linear = self.coef[c] / cell_volume;
                let transfer = self.carried[c] / cell_volume;
                let slip = u_f[c] - u_p[c];
                let b = transfer / slip;
                beta[c] = if slip.abs() > 1e-9 && b.is_finite() && b >= 0.0 { b.min(10.0 * linear) } else { linear };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const R: f64 = 0.003;
    const AREA: f64 = 0.01;
    const DZ: f64 = 0.002;

    /// Grains of heights `z` (radius [`R`]), streamwise velocities `v`, coefficients `k`
    /// and fluctuations `fl`, the fluid velocities their drag saw `seen`, on cells of
    /// [`DZ`] and section [`AREA`] whose fluid moves at `u_f`, in the exact exchange
    /// (`"sphere_average"`) or Maurin's quotient (`"centre"`): beta, the exchange velocity,
    /// and the slips seen + u' - v.
    fn exchange(z: &[f64], v: &[f64], k: &[f64], fl: &[f64], seen: &[f64], exact: bool, u_f: &[f64]) -> [Vec<f64>; 3] {
        let n = u_f.len();
        let mut p = Particles::default();
        for (&z, &v) in z.iter().zip(v) {
            p.push([0.0, 0.0, z], [v, 0.0, 0.0], [0.0; 3], R, 2500.0, false);
        }
        let urx: Vec<f64> = (0..z.len()).map(|a| seen[a] + fl[a] - v[a]).collect();
        let mut s = CellSums::new(n);
        s.accumulate(&p, 0.0, DZ, k, &urx, if exact { Seen::SphereAverage(seen) } else { Seen::Centre });
        let (mut phi, mut up, mut beta) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        s.coupling(AREA * DZ, u_f, &mut phi, &mut up, &mut beta);
        [beta, up, urx]
    }

    /// Up to 20 grains: coefficients k_p >= 0 (0 included), velocities and fluctuations
    /// of either sign, centre heights in `z` (20 of each but k).
    #[allow(clippy::type_complexity)]
    fn grains(z: std::ops::Range<f64>) -> impl Strategy<Value = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>)> {
        let v = || proptest::collection::vec(-0.5f64..0.5, 20);
        (proptest::collection::vec(0.0f64..1e-2, 1..20), v(), v(), proptest::collection::vec(z, 20))
    }

    proptest! {
        #[test]
        fn slices_add_up_to_the_sphere(zc in 0.01f64..1.0, r in 1e-3f64..0.05, dz in 1e-4f64..0.05) {
            // whatever the cut, the slice volumes of a sphere inside the column sum to its volume
            let zc = zc.max(r);
            let n = ((zc + r) / dz).ceil() as usize + 2;
            let mut p = Particles::default();
            p.push([0.0, 0.0, zc], [1.0, 0.0, 0.0], [0.0; 3], r, 1000.0, false);
            let mut s = CellSums::new(n);
            s.accumulate(&p, 0.0, dz, &[0.0], &[0.0], Seen::Centre);
            let total: f64 = s.vol.iter().sum();
            let v = ball_volume(r);
            prop_assert!((total / v - 1.0).abs() < 1e-9);
            prop_assert!(s.vol.iter().all(|w| *w >= -1e-18));
        }

        #[test]
        fn the_fluid_at_the_velocity_the_grains_saw_loses_exactly_their_drag(
            (k, v, fl, z) in grains(0.004..0.056),
            u in -1.0f64..1.0,
            still_mean in proptest::bool::ANY,
        ) {
            // uniform fluid u: every grain saw u, the fluid's loss sum_c beta_c (u - u_p,c)
            // A dz is sum_p F_x,p, whatever the per-grain k, fluctuations and slips (drags
            // against the cell's mean slip, or, with `still_mean`, grains moving with the
            // fluid so that the only slip is u'); every grain inside the column
            let (dz, n) = (0.002, 30);
            let m = k.len();
            let v: Vec<f64> = if still_mean { vec![u; m] } else { v[..m].to_vec() };
            let [beta, up, urx] = exchange(&z[..m], &v, &k, &fl[..m], &vec![u; m], true, &vec![u; n]);
            let fluid: f64 = (0..n).map(|c| beta[c] * (u - up[c]) * AREA * dz).sum();
            let grains: f64 = k.iter().zip(&urx).map(|(k, r)| k * r).sum();
            let scale: f64 = k.iter().zip(&urx).map(|(k, r)| (k * r).abs()).sum::<f64>() + 1e-300;
            prop_assert!((fluid - grains).abs() <= 1e-9 * scale, "{} vs {}", fluid, grains);
            prop_assert!(beta.iter().all(|b| *b >= 0.0 && b.is_finite()));
            prop_assert!(up.iter().all(|x| x.is_finite()));
        }

        #[test]
        fn the_exchange_is_each_grains_drag_linearised_at_its_slices(
            (k, v, fl, z) in grains(-0.002..0.062),
            seen in proptest::collection::vec(-1.0f64..1.0, 20),
            uc in proptest::collection::vec(-1.0f64..1.0, 30),
        ) {
            // any fluid field u_c and any velocities seen: the fluid's loss is
            // sum_p sum_c w_pc (k_p (u_c - u_seen,p) + F_x,p), grains partly outside the
            // column included (their outside share is dropped); it holds no other fluid
            // velocity than the new one
            let (dz, n) = (0.002, 30);
            let m = k.len();
            let [beta, up, urx] = exchange(&z[..m], &v[..m], &k, &fl[..m], &seen[..m], true, &uc);
            let fluid: f64 = (0..n).map(|c| beta[c] * (uc[c] - up[c]) * AREA * dz).sum();
            let vp = ball_volume(R);
            let (mut expected, mut scale) = (0.0, 1e-300);
            for a in 0..m {
                sphere_slices(z[a], R, n, dz, |c, w| {
                    let t = w / vp * (k[a] * (uc[c] - seen[a]) + k[a] * urx[a]);
                    expected += t;
                    scale += w / vp * k[a] * (uc[c].abs() + seen[a].abs() + urx[a].abs());
                });
            }
            prop_assert!((fluid - expected).abs() <= 1e-9 * scale, "{} vs {}", fluid, expected);
            prop_assert!(beta.iter().all(|b| *b >= 0.0));
        }
    }

    proptest! {
        #[test]
        fn grains_that_see_the_sphere_averaged_fluid_hand_it_exactly_their_drag(
            (k, v, fl, z) in grains(0.004..0.056),
            uc in proptest::collection::vec(-1.0f64..1.0, 30),
        ) {
            // any fluid field (a sheared bed surface, a kink): grains whose drag saw
            // the sphere average of the cells (FluidField::sphere_velocity, the drag's
            // velocity) cost the fluid, at that field, exactly sum_p F_x,p
            let (dz, n) = (0.002, 30);
            let m = k.len();
            let mut field = crate::lagrangian::coupling::drag::FluidField::at_rest(n, dz, 0.0);
            field.set_velocity(&uc);
            let seen: Vec<f64> = z[..m].iter().map(|&z| field.sphere_velocity(z, R)).collect();
            let [beta, up, urx] = exchange(&z[..m], &v[..m], &k, &fl[..m], &seen, true, &uc);
            let fluid: f64 = (0..n).map(|c| beta[c] * (uc[c] - up[c]) * AREA * dz).sum();
            let grains: f64 = k.iter().zip(&urx).map(|(k, r)| k * r).sum();
            let scale: f64 = k.iter().zip(&urx).zip(&seen).map(|((k, r), s)| k * (r.abs() + s.abs())).sum::<f64>() + 1e-300;
            prop_assert!((fluid - grains).abs() <= 1e-9 * scale, "{} vs {}", fluid, grains);
        }
    }

    proptest! {
        #[test]
        fn the_drag_velocity_is_the_slice_average_of_the_cells(
            z in -0.01f64..0.07,
            r in 1e-4f64..0.01,
            base in 0.0f64..0.5,
            uc in proptest::collection::vec(-1.0f64..1.0, 30),
        ) {
            // FluidField::sphere_velocity (from the moments) against sum_c V_pc u_c / V_p
            // over the slices of the averaging, spheres across the bottom or the top included
            let (dz, n) = (0.002, 30);
            let mut field = crate::lagrangian::coupling::drag::FluidField::at_rest(n, dz, base);
            field.set_velocity(&uc);
            let mut sum = 0.0;
            sphere_slices(z, r, n, dz, |c, w| sum += w * uc[c]);
            let direct = sum / ball_volume(r);
            let fast = field.sphere_velocity(z + base, r);
            prop_assert!((fast - direct).abs() <= 1e-9, "{} vs {}", fast, direct);
        }
    }

    proptest! {
        #[test]
        fn centre_beta_transfers_the_particle_drag(
            k in proptest::collection::vec(1e-4f64..1e-2, 1..20),
            slip in proptest::collection::vec(0.01f64..0.5, 20),
            z in proptest::collection::vec(0.004f64..0.05, 20),
        ) {
            // "centre": sum_c beta_c (u_f,c - <v>_c) A dz = sum_p F_x,p (Maurin eq 18) when
            // every quotient is used; grains at rest, fluid at 1 m/s, each grain's drag
            // against its own slip (the fluctuation a grain's slip less 1 m/s)
            let (n, m) = (30, k.len());
            let fl: Vec<f64> = slip[..m].iter().map(|s| s - 1.0).collect();
            let [beta, up, urx] = exchange(&z[..m], &vec![0.0; m], &k, &fl, &vec![1.0; m], false, &[1.0; 30]);
            let fluid: f64 = (0..n).map(|c| beta[c] * (1.0 - up[c]) * AREA * DZ).sum();
            let particles: f64 = k.iter().zip(&urx).map(|(k, u)| k * u).sum();
            // capped cells (beta > 10 x linear) cannot occur: slips are within a factor 50
            prop_assert!((fluid / particles - 1.0).abs() < 1e-9, "{} vs {}", fluid, particles);
        }

        #[test]
        fn in_a_uniform_fluid_both_drag_velocities_exchange_alike(
            (k, _, _, z) in grains(0.006..0.054),
            u in -1.0f64..1.0,
            vg in -1.0f64..1.0,
        ) {
            // the sphere average of a uniform field is its centre value (away from the
            // column bottom, where the centre value falls linearly to the wall's 0), and
            // with grains moving together and no fluctuation Maurin's quotient is the
            // linear coefficient: "centre" and "sphere_average" then hand the column the
            // same beta and particle velocity, cell by cell, to round-off
            let (n, m) = (30, k.len());
            let mut field = crate::lagrangian::coupling::drag::FluidField::at_rest(n, DZ, 0.0);
            field.set_velocity(&[u; 30]);
            let centre: Vec<f64> = z[..m].iter().map(|&z| field.velocity(z)).collect();
            let sphere: Vec<f64> = z[..m].iter().map(|&z| field.sphere_velocity(z, R)).collect();
            // the moments lose (H / r)^3 of the float's precision (drag.rs, MOMENT_SPAN)
            for (c, s) in centre.iter().zip(&sphere) {
                prop_assert!((c - s).abs() <= 1e-10, "{} vs {}", c, s);
            }
            let vg = if (vg - u).abs() < 0.1 { u + 0.5 } else { vg };
            let still = vec![vg; m];
            let zero = vec![0.0; m];
            let [bc, uc, _] = exchange(&z[..m], &still, &k, &zero, &centre, false, &[u; 30]);
            let [bs, us, _] = exchange(&z[..m], &still, &k, &zero, &sphere, true, &[u; 30]);
            for c in 0..n {
                prop_assert!((bc[c] - bs[c]).abs() <= 1e-9 * bs[c].abs(), "beta {} vs {} in cell {}", bc[c], bs[c], c);
                if bs[c] > 0.0 {
                    prop_assert!((uc[c] - us[c]).abs() <= 1e-12, "u_p {} vs {} in cell {}", uc[c], us[c], c);
                }
            }
        }
    }

    #[test]
    fn a_cell_without_drag_exchanges_nothing() {
        // grains with k = 0 and an empty column: beta 0, the exchange velocity finite
        let [beta, up, _] = exchange(&[0.01], &[0.3], &[0.0], &[0.1], &[0.5], true, &[0.0; 30]);
        assert!(beta.iter().all(|b| *b == 0.0));
        assert!(up.iter().all(|x| x.is_finite()));
    }
}
