//! The drag coefficient of a two-equation closure's drag damping (Cheng et al. 2018 eqs
//! 23-24) from the grains' cell averages, when the closure asks for the time average of
//! eq 24 ([`saltus_core::closure::turbulence::TwoEquation::slip_average_start`]).
//!
//! ```text
//! beta = (3/4) rho_f C_D(Re*) f(phi, Re_p) |U_r| / d,   Re_p = |U_r| d / nu_f,   (eqs 7, 23)
//! U_r = <u_f - u_s>_t from t_0                                                 (eq 24)
//! ```
//!
//! with u_f - u_s the relative velocity of the phases' cell averages: streamwise the
//! column's velocity less the grains' volume average <v_x>, spanwise -<v_y>, wall-normal
//! w_f - <v_z> = -<v_z> / (1 - phi) (the fluid's w_f from the mixture continuity of the 1D
//! column, (1 - phi) w_f + phi <v_z> = 0). Each cell averages the samples (one per fluid
//! update) in which it holds grains, the only ones where u_s is defined. Before t_0, and in
//! a cell that has had no grain since t_0, U_r is the current relative velocity. Re* and f
//! are the scene's drag law and hindrance with the convention the grains' drag uses.
//!
//! Without the option the closure takes the grains' exchange coefficient (the momentum the
//! fluid loses per unit slip, [`super::averaging`]) over phi: each grain's k_p holds its own
//! instantaneous |u_r|, the eddy interaction model's u' and the grain's velocity fluctuation
//! included, so that the mean of k_p over a cell is the drag coefficient of the mean of
//! |u_r|, larger than that of |<u_r>| (docs/notes/k_omega_dem_coupling.md).

use saltus_core::{DragLaw, Hindrance};

use super::averaging::CellSums;

/// The closures and constants of eq 23.
#[derive(Clone, Copy, Debug)]
pub struct DampingLaw<'a> {
    /// single-particle drag (eq 7)
    pub drag: &'a dyn DragLaw,
    /// hindrance (eqs 12-13)
    pub hindrance: &'a dyn Hindrance,
    /// particle diameter (m)
    pub diameter: f64,
    /// fluid density (kg/m^3)
    pub rho_f: f64,
    /// fluid kinematic viscosity (m^2/s)
    pub nu_f: f64,
}

impl DampingLaw<'_> {
    /// beta of eq 23 (kg m^-3 s^-1) at relative speed `slip` (m/s) and volume fraction
    /// `phi` in [0, 1): (3/4) rho_f f C_D Re* nu_f / (c d^2) with Re* = c Re_p, finite as
    /// the slip vanishes (the Stokes value 18 rho_f nu_f f / (c d^2) for C_D Re* -> 24).
    pub fn beta(&self, slip: f64, phi: f64) -> f64 {
        let d = self.diameter;
        let re_p = slip * d / self.nu_f;
        let c = self.hindrance.reynolds_convention().ratio(phi);
        let re_star = (c * re_p).max(1e-12);
        let f = self.hindrance.factor(phi, re_p);
        0.75 * self.rho_f * f * self.drag.cd_re(re_star) * self.nu_f / (c * d * d)
    }
}

/// Running time averages of the cell-mean relative velocity from t_0 and the drag
/// coefficient of eq 23 they give.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct SlipAverage {
    /// sums of the relative velocity components over the samples since t_0 (m/s)
    sum: [Vec<f64>; 3],
    /// samples in the sums per cell
    count: Vec<u64>,
    /// the current relative velocity components (m/s)
    now: [Vec<f64>; 3],
    /// beta of eq 23 per cell (kg m^-3 s^-1) of the last update
    pub beta: Vec<f64>,
}

impl SlipAverage {
    /// No sample over `n` cells.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self { sum: [z(), z(), z()], count: vec![0; n], now: [z(), z(), z()], beta: z() }
    }

    /// Cells.
    pub fn len(&self) -> usize {
        self.beta.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.beta.is_empty()
    }

    /// Samples per cell since t_0.
    pub fn samples(&self) -> &[u64] {
        &self.count
    }

    /// The relative velocity U_r per cell that beta was last evaluated with: the time
    /// average where the cell has samples, else the current one.
    pub fn relative_velocity(&self, c: usize) -> [f64; 3] {
        let n = self.count[c];
        if n > 0 {
            let inv = 1.0 / n as f64;
            [self.sum[0][c] * inv, self.sum[1][c] * inv, self.sum[2][c] * inv]
        } else {
            [self.now[0][c], self.now[1][c], self.now[2][c]]
        }
    }

    /// Take the cell means of `sums` (the grains of the last fluid update), the fluid
    /// velocity `u_f` and the volume fraction `phi` per cell (each in [0, 1)) at time
    /// `time`, add them to the averages when `time >= start` (t_0), and evaluate beta
    /// per cell with `law`.
    pub fn update(&mut self, time: f64, start: f64, sums: &CellSums, u_f: &[f64], phi: &[f64], law: &DampingLaw<'_>) {
        let average = time >= start;
        for c in 0..self.beta.len() {
            let vol = sums.vol[c];
            let occupied = vol > 0.0;
            let rel = if occupied {
                let inv = 1.0 / vol;
                let eps = 1.0 - phi[c];
                [u_f[c] - sums.v[0][c] * inv, -sums.v[1][c] * inv, -sums.v[2][c] * inv / eps]
            } else {
                [u_f[c], 0.0, 0.0]
            };
            for (m, r) in rel.iter().enumerate() {
                self.now[m][c] = *r;
            }
            if average && occupied {
                for (m, r) in rel.iter().enumerate() {
                    self.sum[m][c] += *r;
                }
                self.count[c] += 1;
            }
            let [x, y, z] = self.relative_velocity(c);
            self.beta[c] = law.beta((x * x + y * y + z * z).sqrt(), phi[c]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use saltus_closures::drag::{HaiderLevenspiel, Stokes};
    use saltus_closures::hindrance::{DiFelice, NoHindrance};

    /// One cell of slice volume 1 holding grains of volume `vol` moving at `v`.
    fn sums(vol: f64, v: [f64; 3]) -> CellSums {
        let mut s = CellSums::new(1);
        s.vol[0] = vol;
        for (m, x) in v.iter().enumerate() {
            s.v[m][0] = vol * x;
        }
        s
    }

    #[test]
    fn eq_24_averages_the_relative_velocity_from_t0_over_the_samples_with_grains() {
        // fluid at 0.5 m/s over grains whose streamwise velocity swings and whose
        // wall-normal velocity swings +-0.05 (alternately faster and slower than the fluid:
        // 0.2 +- 0.45): before t_0 beta takes the current relative
        // velocity, after it the mean of the samples (the empty sample left out); the mean
        // slip (0.3, 0, 0) gives a smaller beta than the swinging one
        let (drag, hindrance) = (HaiderLevenspiel { sphericity: 0.594 }, DiFelice::default());
        let law = DampingLaw { drag: &drag, hindrance: &hindrance, diameter: 3e-3, rho_f: 1000.0, nu_f: 1e-6 };
        let phi = [0.2];
        let mut a = SlipAverage::new(1);
        a.update(0.0, 1.0, &sums(0.2, [0.35, 0.0, 0.05]), &[0.5], &phi, &law);
        let now = (0.15f64 * 0.15 + (0.05 / 0.8) * (0.05 / 0.8)).sqrt();
        assert!((a.beta[0] - law.beta(now, 0.2)).abs() < 1e-9 * a.beta[0]);
        assert_eq!(a.samples()[0], 0);
        let mut swinging = Vec::new();
        for (i, t) in [1.0, 1.1, 1.2, 1.3].iter().enumerate() {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            let v = [0.2 + 0.45 * sign, 0.0, 0.05 * sign];
            a.update(*t, 1.0, &sums(0.2, v), &[0.5], &phi, &law);
            swinging.push(law.beta(((0.3 - 0.45 * sign).powi(2) + (0.05 / 0.8f64).powi(2)).sqrt(), 0.2));
        }
        a.update(1.4, 1.0, &sums(0.0, [0.0; 3]), &[0.5], &phi, &law);
        assert_eq!(a.samples()[0], 4);
        let ur = a.relative_velocity(0);
        assert!((ur[0] - 0.3).abs() < 1e-12 && ur[1].abs() < 1e-12 && ur[2].abs() < 1e-12, "{ur:?}");
        assert!((a.beta[0] - law.beta(0.3, 0.2)).abs() < 1e-9 * a.beta[0]);
        let mean_swinging = swinging.iter().sum::<f64>() / 4.0;
        assert!(a.beta[0] < 0.95 * mean_swinging, "{} against {mean_swinging}", a.beta[0]);
    }

    #[test]
    fn the_stokes_coefficient_is_18_rho_nu_over_d2() {
        // C_D = 24/Re_p without hindrance: beta = 18 mu / d^2 at any slip (Stokes drag
        // per unit particle volume over the slip)
        let (drag, hindrance) = (Stokes {}, NoHindrance {});
        let law = DampingLaw { drag: &drag, hindrance: &hindrance, diameter: 1e-3, rho_f: 1000.0, nu_f: 1e-6 };
        for slip in [0.0, 1e-3, 0.1] {
            let b = law.beta(slip, 0.0);
            assert!((b / (18.0 * 1e-3 / 1e-6) - 1.0).abs() < 1e-12, "{b}");
        }
    }
}
