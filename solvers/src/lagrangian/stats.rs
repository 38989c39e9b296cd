//! Time-averaged profiles and the steady-state test.
//!
//! Each sample (one per fluid update after `solver.lagrangian.stats_start`) adds the slice sums of
//! [`super::averaging::CellSums`] and the fluid fields. The averages are taken over space
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

use super::averaging::CellSums;
pub use super::blocking::{BlockEstimate, Blocking, NoEstimate, BLOCK_LEVELS, LONG_BLOCKS, MIN_BLOCKS};

/// Running sums of the profiles.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    /// samples taken
    pub samples: usize,
    pub(super) vol: Vec<f64>,
    pub(super) v: [Vec<f64>; 3],
    pub(super) vv: [Vec<f64>; 4],
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

/// Steady-state test on the transport rate: window means compared between consecutive
/// windows.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Steady {
    window: f64,
    tolerance: f64,
    needed: usize,
    start: f64,
    sum: f64,
    count: usize,
    last: Option<f64>,
    streak: usize,
    /// last relative change between windows (infinite before two windows)
    change: f64,
}

impl Steady {
    /// Windows of `window` s, steady after `needed` consecutive relative changes below
    /// `tolerance`.
    pub fn new(window: f64, tolerance: f64, needed: usize) -> Self {
        Self { window, tolerance, needed, change: f64::INFINITY, ..Default::default() }
    }

    /// Add the instantaneous transport rate `qs` at time `t`; true once steady.
    pub fn add(&mut self, t: f64, qs: f64) -> bool {
        if self.count == 0 {
            self.start = t;
        }
        self.sum += qs;
        self.count += 1;
        if t - self.start >= self.window {
            let mean = self.sum / self.count as f64;
            if let Some(prev) = self.last {
                let scale = mean.abs().max(prev.abs());
                self.change = if scale > 0.0 { (mean - prev).abs() / scale } else { 0.0 };
                self.streak = if self.change <= self.tolerance { self.streak + 1 } else { 0 };
            }
            self.last = Some(mean);
            self.sum = 0.0;
            self.count = 0;
        }
        self.is_steady()
    }

    /// Last relative change between consecutive windows, once there were two.
    pub fn change(&self) -> Option<f64> {
        self.change.is_finite().then_some(self.change)
    }

    /// Whether the criterion is met.
    pub fn is_steady(&self) -> bool {
        self.streak >= self.needed
    }

    /// Window length (s), tolerance on the relative change, consecutive windows needed.
    pub fn criterion(&self) -> (f64, f64, usize) {
        (self.window, self.tolerance, self.needed)
    }

    /// Consecutive windows so far whose change was within the tolerance.
    pub fn streak(&self) -> usize {
        self.streak
    }
}

/// The granular temperature history of a run without fluid, and its comparison with
/// Haff's law T(t) = T0 / (1 + t/tau)^2 (P. K. Haff, J. Fluid Mech. 134, 401 (1983)) when
/// the scene is a homogeneous cooling one. Fixed size: running sums only.
///
/// tau = sqrt(pi) d / (4 (1 - e^2) phi g0 sqrt(T0)) is the kinetic-theory cooling time of
/// Chassagne et al. 2023 eqs 2.16 and 2.22 ((3/2) phi dT/dt = -F4 T^{3/2} / d,
/// F4 = 12/sqrt(pi) (1 - e^2) phi^2 g0, Carnahan-Starling g0). The fitted time comes from
/// the least squares of 1/sqrt(T) against t, which Haff's law makes a straight line of
/// intercept 1/sqrt(T0) and slope 1/(tau sqrt(T0)).
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Cooling {
    /// temperature samples taken
    pub samples: u64,
    /// temperature of the first sample, at the start of the flow (m^2/s^2)
    pub initial: f64,
    /// time (s) and temperature (m^2/s^2) of the last sample
    pub last: (f64, f64),
    /// largest |T / T_Haff - 1| over the samples (with a Haff time)
    pub max_deviation: f64,
    sums: [f64; 5],
}

impl Cooling {
    /// Add the temperature `temp` at time `t`; `haff` is sqrt(pi) d / (4 (1 - e^2) phi
    /// g0) (s (m/s)), when the scene is a cooling one.
    pub fn add(&mut self, t: f64, temp: f64, haff: Option<f64>) {
        if self.samples == 0 {
            self.initial = temp;
        }
        self.samples += 1;
        self.last = (t, temp);
        if temp > 0.0 {
            let y = 1.0 / temp.sqrt();
            for (s, x) in self.sums.iter_mut().zip([1.0, t, y, t * y, t * t]) {
                *s += x;
            }
        }
        if let Some(tau) = haff.and_then(|h| self.haff_tau(h)) {
            let predicted = self.initial / (1.0 + t / tau).powi(2);
            self.max_deviation = self.max_deviation.max((temp / predicted - 1.0).abs());
        }
    }

    /// Haff time tau (s) of the initial temperature, from the constant of [`Cooling::add`].
    pub fn haff_tau(&self, haff: f64) -> Option<f64> {
        (self.samples > 0 && self.initial > 0.0).then(|| haff / self.initial.sqrt())
    }

    /// Haff's temperature at time `t` (m^2/s^2).
    pub fn haff_at(&self, haff: f64, t: f64) -> Option<f64> {
        self.haff_tau(haff).map(|tau| self.initial / (1.0 + t / tau).powi(2))
    }

    /// Cooling time fitted to the history (s): intercept over slope of 1/sqrt(T) against
    /// t; `None` with fewer than three samples or no cooling.
    pub fn fitted_tau(&self) -> Option<f64> {
        let [n, st, sy, sty, stt] = self.sums;
        if n < 3.0 {
            return None;
        }
        let sxx = stt - st * st / n;
        let slope = (sty - st * sy / n) / sxx;
        let intercept = (sy - slope * st) / n;
        let tau = intercept / slope;
        (slope > 0.0 && tau.is_finite()).then_some(tau)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng as _;
    use rand_distr::{Distribution as _, StandardNormal};

    /// `n` samples of the AR(1) series x_t = a x_{t-1} + sqrt(1 - a^2) sigma eps_t,
    /// started in its stationary law (variance sigma^2), around `mean`.
    fn ar1(n: usize, a: f64, sigma: f64, mean: f64, seed: u64) -> Blocking {
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut eps = || -> f64 { StandardNormal.sample(&mut rng) };
        let mut b = Blocking::new();
        let mut x = sigma * eps();
        for _ in 0..n {
            b.add(mean + x);
            x = a * x + (1.0 - a * a).sqrt() * sigma * eps();
        }
        b
    }

    /// Exact standard error of the mean of `n` stationary AR(1) samples:
    /// Var = sigma^2 / n [(1 + a)/(1 - a) - 2 a (1 - a^n) / (n (1 - a)^2)].
    fn ar1_stderr(n: usize, a: f64, sigma: f64) -> f64 {
        let nf = n as f64;
        (sigma * sigma / nf * ((1.0 + a) / (1.0 - a) - 2.0 * a * (1.0 - a.powi(n as i32)) / (nf * (1.0 - a).powi(2))))
            .sqrt()
    }

    #[test]
    fn blocking_recovers_the_standard_error_of_an_ar1_series() {
        // correlation time -1/ln(a): 9.5 samples at a = 0.9, 99.5 at a = 0.99; 2^18
        // samples. The blocking estimate's own error is 1/sqrt(2 (n_blocks - 1)) (about 2 %
        // at a = 0.9, 5 % at 0.99) plus the bias of the residual correlation between blocks:
        // each realisation within 12 %, the mean of 8 seeds within 5 %.
        let n = 1 << 18;
        for (a, sigma, mean) in [(0.0, 1.0, 0.0), (0.9, 0.3, 5.0), (0.99, 2.0, -1.0)] {
            let exact = ar1_stderr(n, a, sigma);
            let mut ratios = Vec::new();
            for seed in 0..8 {
                let b = ar1(n, a, sigma, mean, seed);
                assert_eq!(b.samples(), n as u64);
                let e = b.estimate().unwrap_or_else(|why| panic!("a = {a}, seed {seed}: {why}"));
                let r = e.stderr / exact;
                assert!((r - 1.0).abs() < 0.12, "a = {a}, seed {seed}: {} vs exact {exact} ({e:?})", e.stderr);
                assert!(e.blocks >= MIN_BLOCKS);
                ratios.push(r);
            }
            let mean_ratio = ratios.iter().sum::<f64>() / ratios.len() as f64;
            eprintln!("a = {a}: estimated / exact standard error {mean_ratio:.4} ({ratios:.3?})");
            assert!((mean_ratio - 1.0).abs() < 0.05, "a = {a}: mean ratio {mean_ratio}");
        }
    }

    #[test]
    fn blocking_mean_is_the_sample_mean() {
        let xs: Vec<f64> = (0..1000).map(|i| 1e-3 * (1.0 + 0.1 * ((i * 7919) % 13) as f64)).collect();
        let mut b = Blocking::new();
        xs.iter().for_each(|x| b.add(*x));
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        assert!((b.mean().unwrap_or(f64::NAN) / mean - 1.0).abs() < 1e-14);
    }

    #[test]
    fn no_standard_error_from_too_few_or_too_correlated_samples() {
        let mut b = Blocking::new();
        assert_eq!(b.mean(), None);
        for i in 0..(2 * MIN_BLOCKS - 1) {
            b.add(i as f64);
        }
        assert_eq!(b.estimate(), Err(NoEstimate::TooFewSamples { samples: 2 * MIN_BLOCKS - 1 }));
        // a correlation time of 1000 samples in 4096 samples: no level is both
        // uncorrelated and made of 8 blocks
        let b = ar1(4096, 0.999, 1.0, 0.0, 3);
        assert!(matches!(b.estimate(), Err(NoEstimate::TooFewBlocks { .. })), "{:?}", b.estimate());
        // a constant series has a zero standard error, not a missing one
        let mut b = Blocking::new();
        (0..100).for_each(|_| b.add(0.25));
        assert_eq!(b.estimate().map(|e| e.stderr), Ok(0.0));
    }

    #[test]
    fn cooling_fit_of_an_exact_haff_history_gives_its_time() {
        let (t0, tau): (f64, f64) = (0.01, 1.3);
        let haff = tau * t0.sqrt();
        let mut c = Cooling::default();
        for k in 0..=100 {
            let t = 0.05 * k as f64;
            c.add(t, t0 / (1.0 + t / tau).powi(2), Some(haff));
        }
        assert!((c.fitted_tau().unwrap_or(0.0) / tau - 1.0).abs() < 1e-9);
        assert!(c.max_deviation < 1e-12 && (c.haff_tau(haff).unwrap_or(0.0) - tau).abs() < 1e-12);
        assert!((c.haff_at(haff, c.last.0).unwrap_or(0.0) / c.last.1 - 1.0).abs() < 1e-12);
    }
}
