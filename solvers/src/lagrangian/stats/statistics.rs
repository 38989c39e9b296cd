//! Time-averaged profiles.
//!
//! Each sample (one per fluid update after `solver.lagrangian.stats_start`) adds the slice sums of
//! [`CellSums`] and the fluid fields. The averages are taken over space
//! and time together:
//!
//! ```text
//! phi = <sum V_pc>_t / (A dz),   <v> = <sum V_pc v>_t / <sum V_pc>_t,
//! <v'_i v'_j> = <sum V_pc v_i v_j>_t / <sum V_pc>_t - <v_i><v_j>,
//! T = (<v'_x^2> + <v'_y^2> + <v'_z^2>) / 3,    q_s = phi <v_x>
//! ```
//!
//! (the kinetic part of the granular stress, Chassagne et al. 2023 eq 2.27, and the
//! transport-rate density of Maurin 2015 eq 20).

use super::blocking::Blocking;
use super::cooling::Cooling;
use crate::lagrangian::coupling::averaging::CellSums;

/// Running sums of the profiles.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    /// samples taken
    pub samples: usize,
    pub(crate) vol: Vec<f64>,
    pub(crate) v: [Vec<f64>; 3],
    pub(crate) vv: [Vec<f64>; 4],
    u_f: Vec<f64>,
    reynolds: Vec<f64>,
    nu_t: Vec<f64>,
    beta: Vec<f64>,
    tau_face: Vec<f64>,
    /// the instantaneous transport rate of each sample (m^2/s), blocked for its standard
    /// error
    pub qs: Blocking,
    /// granular temperature history of a run without fluid (no averaging sample)
    pub cooling: Cooling,
}

/// Finished time-averaged profiles per cell.
#[derive(Clone, Debug, Default)]
pub struct Averaged {
    /// volume fraction
    pub phi: Vec<f64>,
    /// mean particle velocity components (m/s)
    pub v: [Vec<f64>; 3],
    /// fluctuation variances xx, yy, zz and covariance xz (m^2/s^2)
    pub vv: [Vec<f64>; 4],
    /// granular temperature (m^2/s^2)
    pub temperature: Vec<f64>,
    /// transport-rate density phi <v_x> (m/s)
    pub q_s: Vec<f64>,
    /// fluid velocity (m/s)
    pub u_f: Vec<f64>,
    /// Reynolds shear stress R_xz (Pa)
    pub tau_t: Vec<f64>,
    /// eddy viscosity (m^2/s)
    pub nu_t: Vec<f64>,
    /// drag coefficient beta (kg m^-3 s^-1)
    pub beta: Vec<f64>,
    /// total fluid shear stress at the faces (Pa)
    pub tau_face: Vec<f64>,
}

impl Stats {
    /// Empty sums over `n` cells.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self {
            samples: 0,
            vol: z(),
            v: [z(), z(), z()],
            vv: [z(), z(), z(), z()],
            u_f: z(),
            reynolds: z(),
            nu_t: z(),
            beta: z(),
            tau_face: vec![0.0; n + 1],
            qs: Blocking::new(),
            cooling: Cooling::default(),
        }
    }

    /// Add one sample: particle slice sums, fluid velocity, Reynolds stress (Pa), eddy
    /// viscosity, beta, face shear stresses and the transport rate of these sums
    /// (m^2/s), whose time average is the summary's qs.
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        s: &CellSums,
        u_f: &[f64],
        tau_t: &[f64],
        nu_t: &[f64],
        beta: &[f64],
        tau_face: &[f64],
        qs: f64,
    ) {
        self.qs.add(qs);
        let acc = |dst: &mut Vec<f64>, src: &[f64]| dst.iter_mut().zip(src).for_each(|(d, s)| *d += s);
        acc(&mut self.vol, &s.vol);
        for k in 0..3 {
            acc(&mut self.v[k], &s.v[k]);
        }
        for k in 0..4 {
            acc(&mut self.vv[k], &s.vv[k]);
        }
        acc(&mut self.u_f, u_f);
        acc(&mut self.reynolds, tau_t);
        acc(&mut self.nu_t, nu_t);
        acc(&mut self.beta, beta);
        acc(&mut self.tau_face, tau_face);
        self.samples += 1;
    }

    /// The time-averaged profiles for slices of volume `cell_volume` (zeros before the
    /// first sample).
    pub fn averaged(&self, cell_volume: f64) -> Averaged {
        let n = self.vol.len();
        let ns = self.samples.max(1) as f64;
        let mean = |v: &[f64]| v.iter().map(|x| x / ns).collect::<Vec<f64>>();
        let per_vol = |v: &[f64]| -> Vec<f64> {
            v.iter().zip(&self.vol).map(|(x, w)| if *w > 0.0 { x / w } else { 0.0 }).collect()
        };
        let v = [per_vol(&self.v[0]), per_vol(&self.v[1]), per_vol(&self.v[2])];
        let raw = [per_vol(&self.vv[0]), per_vol(&self.vv[1]), per_vol(&self.vv[2]), per_vol(&self.vv[3])];
        let pairs = [(0, 0), (1, 1), (2, 2), (0, 2)];
        let vv: [Vec<f64>; 4] = std::array::from_fn(|k| {
            let (a, b) = pairs[k];
            (0..n)
                .map(|c| if self.vol[c] > 0.0 { raw[k][c] - v[a][c] * v[b][c] } else { 0.0 })
                .map(|x| if k < 3 { x.max(0.0) } else { x })
                .collect()
        });
        let temperature = (0..n).map(|c| (vv[0][c] + vv[1][c] + vv[2][c]) / 3.0).collect();
        let phi: Vec<f64> = self.vol.iter().map(|w| w / ns / cell_volume).collect();
        let q_s = phi.iter().zip(&v[0]).map(|(p, u)| p * u).collect();
        Averaged {
            phi,
            v,
            vv,
            temperature,
            q_s,
            u_f: mean(&self.u_f),
            tau_t: mean(&self.reynolds),
            nu_t: mean(&self.nu_t),
            beta: mean(&self.beta),
            tau_face: mean(&self.tau_face),
        }
    }
}
