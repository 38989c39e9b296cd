//! The volume fraction the fluid reads: the time mean of the slice volumes over the DEM
//! steps of a fluid period (Cheng, Chauchat, Hsu & Calantoni eq 14,
//! `solver.lagrangian.phi_average = "fluid_period"`) and its diffusion over one fluid
//! period (their eq 17, `solver.lagrangian.phi_diffusion` = L_d / d).
//!
//! ```text
//! eq 14:  phi_c = (1 / N_s) sum_{j=1}^{N_s} phi_c,j,   phi_c,j = sum_p V_pc(z_p(t_j)) / (A dz)
//! eq 17:  d phi / dt = d/dz (D_t d phi / dz),   D_t = L_d^2 / tau_f
//! ```
//!
//! phi_c,j are the exact slice volumes of [`super::averaging`] after the DEM step j of the
//! period that ends at the fluid update (N_s = the steps since the last update; 1 at the
//! first update). Eq 17 is integrated over one fluid period tau_f by one backward-Euler
//! step, as the peer CFDEM code's `constDiffSmoothing` solves it (one implicit
//! `fvm::laplacian` per coupling step), on the column's cells with no flux through the
//! bottom and the top:
//!
//! ```text
//! phi_c - a (phi_{c-1} - 2 phi_c + phi_{c+1}) = phi*_c,   a = D_t tau_f / dz^2 = (L_d / dz)^2
//! ```
//!
//! (a mirrored neighbour at both ends). The matrix is symmetric with unit row sums, so the
//! sum of phi over the cells is kept to round-off, and an M-matrix, so the smoothed phi
//! stays within the range of phi* (no new maximum: phi <= 0.99 still holds); the discrete
//! cosine mode cos(pi m (c + 1/2) / n) is damped by 1 / (1 + 4 a sin^2(pi m / (2 n))).
//! Cheng takes L_d = d (after eq 17: "stable and necessary when the fluid grid length is
//! similar to or smaller than the particle diameter"; the DEM's column here has cells of
//! d / 7 to d / 30). The smoothed field is the fluid's (the column's coupling, the drag
//! damping and the particles' hindrance, which read the fluid's field); the profiles and
//! the transport rate reported are the DEM's own slice averages, as Cheng's are.

use serde::{Deserialize, Serialize};

use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::engine::slicing::sphere_slices;

/// Sums of the slice volumes over the DEM steps since the last fluid update (eq 14).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhiWindow {
    /// sum over the steps of the slice volumes per cell (m^3); empty when the scene does
    /// not ask for the time mean
    pub vol: Vec<f64>,
    /// DEM steps summed
    pub steps: u64,
}

impl PhiWindow {
    /// Sums over `n` cells (none for `n = 0`: the option is off).
    pub fn new(n: usize) -> Self {
        Self { vol: vec![0.0; n], steps: 0 }
    }

    /// Add the slice volumes of every particle at its current height (`base` the column
    /// bottom in particle coordinates, cells of height `dz`). Sequential, in particle
    /// order: bit-reproducible; no allocation.
    pub fn add(&mut self, p: &Particles, base: f64, dz: f64) {
        let n = self.vol.len();
        if n == 0 {
            return;
        }
        let vol = &mut self.vol;
        for (&z, &r) in p.z.iter().zip(&p.radius) {
            sphere_slices(z - base, r, n, dz, |c, w| vol[c] += w);
        }
        self.steps += 1;
    }

    /// Write the time mean phi_c = sum / (N_s A dz) into `phi` and start the next window;
    /// `false` (nothing written) when no step was summed.
    pub fn take_mean(&mut self, cell_volume: f64, phi: &mut [f64]) -> bool {
        if self.steps == 0 {
            return false;
        }
        let scale = 1.0 / (self.steps as f64 * cell_volume);
        for (f, v) in phi.iter_mut().zip(&mut self.vol) {
            *f = *v * scale;
            *v = 0.0;
        }
        self.steps = 0;
        true
    }
}

/// One backward-Euler step of eq 17 over the cells, in place, with a = (L_d / dz)^2 and
/// no flux through the ends (module documentation). `scratch` is resized to the cell count
/// once and reused. a <= 0 or a single cell: nothing changes.
pub fn diffuse(phi: &mut [f64], a: f64, scratch: &mut Vec<f64>) {
    let n = phi.len();
    if n < 2 || a <= 0.0 {
        return;
    }
    scratch.resize(n, 0.0);
    // Thomas algorithm on -a x_{c-1} + b_c x_c - a x_{c+1} = phi_c, b = 1 + 2a (1 + a at
    // the ends); scratch holds the modified upper diagonal
    let mut b = 1.0 + a;
    scratch[0] = -a / b;
    phi[0] /= b;
    for c in 1..n {
        let diag = if c == n - 1 { 1.0 + a } else { 1.0 + 2.0 * a };
        b = diag + a * scratch[c - 1];
        scratch[c] = -a / b;
        phi[c] = (phi[c] + a * phi[c - 1]) / b;
    }
    for c in (0..n - 1).rev() {
        phi[c] -= scratch[c] * phi[c + 1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use saltus_core::grain::ball_volume;

    proptest! {
        #[test]
        fn diffusion_keeps_the_mean_and_the_bounds(
            phi in proptest::collection::vec(0.0f64..0.64, 2..200),
            ld in 0.0f64..10.0,
        ) {
            // unit row and column sums: sum phi kept; M-matrix: no new extremum
            let a = ld * ld;
            let mut s = phi.clone();
            diffuse(&mut s, a, &mut Vec::new());
            let (before, after): (f64, f64) = (phi.iter().sum(), s.iter().sum());
            prop_assert!((after - before).abs() <= 1e-12 * (1.0 + before), "{} vs {}", after, before);
            let (lo, hi) = phi.iter().fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
            prop_assert!(s.iter().all(|&x| x >= lo - 1e-12 && x <= hi + 1e-12));
        }

        #[test]
        fn diffusion_damps_each_cosine_mode_at_the_rate_of_eq_17(
            n in 4usize..120,
            m_frac in 0.0f64..1.0,
            ld in 0.01f64..10.0,
            amp in 0.01f64..0.2,
        ) {
            // phi = 0.3 + amp cos(pi m (c + 1/2) / n): the implicit step of D_t = L_d^2 / tau_f
            // over tau_f keeps 0.3 and multiplies the mode by 1 / (1 + 4 a sin^2(pi m / 2n))
            let m = 1 + ((n - 2) as f64 * m_frac) as usize;
            let a = ld * ld;
            let k = std::f64::consts::PI * m as f64 / n as f64;
            let mode: Vec<f64> = (0..n).map(|c| (k * (c as f64 + 0.5)).cos()).collect();
            let mut phi: Vec<f64> = mode.iter().map(|x| 0.3 + amp * x).collect();
            diffuse(&mut phi, a, &mut Vec::new());
            let g = 1.0 / (1.0 + 4.0 * a * (k / 2.0).sin().powi(2));
            for c in 0..n {
                let want = 0.3 + amp * g * mode[c];
                prop_assert!((phi[c] - want).abs() <= 1e-12, "cell {}: {} vs {}", c, phi[c], want);
            }
        }
    }

    #[test]
    fn a_long_diffusion_length_levels_a_step_and_a_short_one_leaves_it() {
        // the limits of a = (L_d / dz)^2: -> infinity, the mean everywhere; -> 0, unchanged
        let step: Vec<f64> = (0..40).map(|c| if c < 20 { 0.6 } else { 0.0 }).collect();
        let mut wide = step.clone();
        diffuse(&mut wide, 1e12, &mut Vec::new());
        assert!(wide.iter().all(|x| (x - 0.3).abs() < 1e-6), "{wide:?}");
        let mut narrow = step.clone();
        diffuse(&mut narrow, 1e-14, &mut Vec::new());
        assert!(narrow.iter().zip(&step).all(|(x, y)| (x - y).abs() < 1e-12));
    }

    #[test]
    fn the_period_mean_of_a_grain_crossing_a_face_at_constant_speed_is_the_time_mean() {
        // a sphere of radius R moving up at constant speed w from centre height z0: over
        // N steps of dt, the mean slice volume of each cell is (1 / N) sum_j V_c(z0 + j w dt),
        // which for N -> infinity is the time integral (1 / T) int_0^T V_c dt; for the cell
        // [0, h) with the sphere crossing its top face from fully inside to fully above,
        // V_c = cap_volume(z(t), R, h) and the integral is (1 / 2R) int cap ds with s from
        // 2R to 0, i.e. the ball's volume times 1/2 (cap(s) + cap(2R - s) = V)
        let (r, h, dz) = (0.001, 0.004, 0.004);
        let n_steps = 20_000u64;
        // centre from h - r (just inside) to h + r (just above): distance 2R
        let (z0, w_dt) = (h - r, 2.0 * r / n_steps as f64);
        let mut p = Particles::default();
        p.push([0.0, 0.0, z0], [0.0; 3], [0.0; 3], r, 2500.0, false);
        let mut win = PhiWindow::new(2);
        for j in 0..n_steps {
            p.z[0] = z0 + (j as f64 + 0.5) * w_dt;
            win.add(&p, 0.0, dz);
        }
        let mut phi = vec![0.0; 2];
        assert!(win.take_mean(1.0, &mut phi));
        let v = ball_volume(r);
        // the midpoint rule's error is O((w dt / R)^2)
        assert!((phi[0] / v - 0.5).abs() < 1e-6, "{}", phi[0] / v);
        assert!((phi[1] / v - 0.5).abs() < 1e-6, "{}", phi[1] / v);
        // the window restarts empty
        assert_eq!(win.steps, 0);
        assert!(win.vol.iter().all(|&x| x == 0.0));
        assert!(!win.take_mean(1.0, &mut phi));
    }

    #[test]
    fn the_period_mean_of_an_oscillating_grain_is_the_analytic_time_mean() {
        // centre z(t) = zc + A sin(2 pi t / T) over one period, cell boundary at zc: the
        // slice below the face holds cap(zc; z(t)); its time mean over a period equals
        // (1/T) int_0^T cap dt, computed here by a fine quadrature of the closed-form cap,
        // and by symmetry (sin odd about the face) it is half the ball: V / 2
        let (r, dz) = (0.001, 0.003);
        let zc = dz;
        let amp = 0.6 * r;
        let n_steps = 10_000u64;
        let mut p = Particles::default();
        p.push([0.0, 0.0, zc], [0.0; 3], [0.0; 3], r, 2500.0, false);
        let mut win = PhiWindow::new(2);
        for j in 0..n_steps {
            let t = j as f64 / n_steps as f64;
            p.z[0] = zc + amp * (2.0 * std::f64::consts::PI * t).sin();
            win.add(&p, 0.0, dz);
        }
        let mut phi = vec![0.0; 2];
        win.take_mean(1.0, &mut phi);
        let v = ball_volume(r);
        assert!((phi[0] / v - 0.5).abs() < 1e-9, "{}", phi[0] / v);
        assert!(((phi[0] + phi[1]) / v - 1.0).abs() < 1e-12);
        // while any single step's slice is not the mean (the one-step slice of eq 6)
        let one = crate::lagrangian::engine::slicing::cap_volume(zc + amp, r, zc) / v;
        assert!((one - 0.5).abs() > 0.2, "{one}");
    }
}
