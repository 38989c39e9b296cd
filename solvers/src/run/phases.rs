//! Phase averages of a run under a periodic forcing, for both solvers, as one observer of
//! the driver ([`PhaseAverages`]): after `output.spin_up_periods` whole periods, every
//! unit of work adds its transport rate and profiles, weighted by the time it covers, to
//! the bin of its phase (`output.phases` bins over the period). Only whole periods count:
//! the transport integrated over each period gives the net transport per period, whose
//! statistical error is the standard error of the per-period values (each period one
//! block: the blocks of a periodic state are independent when the state has forgotten
//! its start), and the error of each phase bin's qs is that of its per-period means.
//!
//! Written at the end: `phases.csv` (one row per bin: phase, forcing signal at the bin
//! centre, qs and its error), `phase_profiles.csv` (the profiles of each bin, one block of
//! rows per bin) and `phases.json` (period, periods averaged, net transport per period and
//! its error).

use std::fmt::Write as _;
use std::path::Path;

use saltus_core::scene::{Forcing, Scene};
use saltus_core::Error;
use serde::Serialize;

use super::{Clock, Control, Observer, Phase, Progress, Stepper};
use crate::output::Profiles;

/// File of the phase-binned transport rate.
pub const PHASES: &str = "phases.csv";
/// Header of [`PHASES`].
pub const PHASES_HEADER: &str = "phase,t_over_period,forcing,qs,qs_error,periods";
/// File of the phase-binned profiles.
pub const PHASE_PROFILES: &str = "phase_profiles.csv";
/// File of the net transport per period.
pub const PHASES_SUMMARY: &str = "phases.json";

/// The net transport of the phase averages.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NetTransport {
    /// forcing period (s)
    pub period: f64,
    /// phase bins
    pub bins: usize,
    /// whole periods left out at the start
    pub spin_up_periods: usize,
    /// whole periods averaged
    pub periods: usize,
    /// mean over the periods of the integral of qs over a period (m^2)
    pub per_period: Option<f64>,
    /// its standard error over the periods (m^2), with two periods or more
    pub error: Option<f64>,
    /// the period-averaged transport rate per_period / period (m^2/s)
    pub mean_qs: Option<f64>,
}

/// Sums of one whole period.
#[derive(Clone, Debug, Default)]
struct PeriodSums {
    /// integral of qs over each bin's share of the period and the time of it
    qs: Vec<f64>,
    time: Vec<f64>,
}

/// A state the run passed through: its time, transport rate and (when taken) profiles.
#[derive(Clone, Debug)]
struct Sample {
    t: f64,
    qs: f64,
    profiles: Option<Vec<Vec<f64>>>,
}

/// The phase-averaging observer (see the module documentation).
#[derive(Clone, Debug)]
pub struct PhaseAverages {
    period: f64,
    bins: usize,
    spin_up: usize,
    /// the last state seen
    last: Option<Sample>,
    /// the period being filled, by index from the start
    current: Option<(usize, PeriodSums)>,
    /// whole periods
    done: Vec<PeriodSums>,
    /// profiles: the names, the z of the first, the time-weighted sums per bin of the
    /// period being filled, and of the whole periods, with their weights
    names: Vec<String>,
    z: Vec<f64>,
    filling: Vec<Vec<Vec<f64>>>,
    filling_weight: Vec<f64>,
    profiles: Vec<Vec<Vec<f64>>>,
    profile_weight: Vec<f64>,
}

impl PhaseAverages {
    /// Averages over `bins` phases of `period` (s) after `spin_up` whole periods.
    pub fn new(period: f64, bins: usize, spin_up: usize) -> Self {
        Self {
            period,
            bins,
            spin_up,
            last: None,
            current: None,
            done: Vec::new(),
            names: Vec::new(),
            z: Vec::new(),
            filling: vec![Vec::new(); bins],
            filling_weight: vec![0.0; bins],
            profiles: vec![Vec::new(); bins],
            profile_weight: vec![0.0; bins],
        }
    }

    /// The observer of `scene` when it asks for phase averages (`output.phases` > 0 with a
    /// periodic forcing, as its loading checked).
    pub fn of_scene(scene: &Scene) -> Option<Self> {
        let period = scene.physics.forcing.as_ref().and_then(Forcing::period)?;
        (scene.output.phases > 0).then(|| Self::new(period, scene.output.phases, scene.output.spin_up_periods))
    }

    /// Whether a state at `t` (s), following the last one, needs its profiles: when the
    /// time up to it or up to a next state as far on reaches the averaged periods.
    fn wants_profiles(&self, t: f64) -> bool {
        let last = self.last.as_ref().map_or(t, |s| s.t);
        t + (t - last).max(0.0) >= self.spin_up as f64 * self.period
    }

    /// Add the state at flow time `t` (s): its transport rate `qs` (m^2/s) and, when
    /// given, its profiles. The run between the last state and this one is taken as linear
    /// in time (the trapezoidal rule, second order in the step like the solvers), cut at
    /// the edges of the phase bins and periods; the first state only opens the record.
    pub fn add(&mut self, t: f64, qs: Option<f64>, profiles: Option<Profiles>) {
        let values = profiles.map(|p| {
            let mut columns = p.columns.into_iter();
            let z = columns.next().map(|(_, z)| z).unwrap_or_default();
            let (names, values): (Vec<String>, Vec<Vec<f64>>) = columns.unzip();
            if self.names.is_empty() {
                (self.names, self.z) = (names, z);
            }
            values
        });
        let now = Sample { t, qs: qs.filter(|q| q.is_finite()).unwrap_or(0.0), profiles: values };
        if let Some(before) = self.last.take() {
            let dt = now.t - before.t;
            if dt.is_finite() && dt > 0.0 {
                self.integrate(&before, &now);
            }
        }
        self.last = Some(now);
    }

    /// Add the linear interpolation between `a` and `b` over [a.t, b.t].
    fn integrate(&mut self, a: &Sample, b: &Sample) {
        let width = self.period / self.bins as f64;
        let dt = b.t - a.t;
        let mut from = a.t;
        while from < b.t {
            // the bin holding `from` and its end
            let s = from / width;
            let mut index = s.floor();
            // an edge reached by rounding belongs to the next bin
            if (index + 1.0) * width <= from {
                index += 1.0;
            }
            let to = ((index + 1.0) * width).min(b.t);
            if to.partial_cmp(&from) != Some(std::cmp::Ordering::Greater) || !index.is_finite() {
                break;
            }
            let k = (index / self.bins as f64).floor();
            if k >= self.spin_up as f64 {
                let k = k as usize;
                let bin = ((index as usize) % self.bins).min(self.bins - 1);
                // a linear function's integral is the piece's length times its middle value
                let w = (0.5 * (from + to) - a.t) / dt;
                self.accumulate(k, bin, to - from, w, a, b);
            }
            from = to;
        }
    }

    fn accumulate(&mut self, k: usize, bin: usize, length: f64, w: f64, a: &Sample, b: &Sample) {
        if self.current.as_ref().is_some_and(|(i, _)| *i != k) {
            self.close();
        }
        let bins = self.bins;
        let (_, sums) =
            self.current.get_or_insert_with(|| (k, PeriodSums { qs: vec![0.0; bins], time: vec![0.0; bins] }));
        sums.qs[bin] += ((1.0 - w) * a.qs + w * b.qs) * length;
        sums.time[bin] += length;
        // a state taken without profiles (the one before the first averaged) stands for
        // its neighbour's
        let Some(pb) = b.profiles.as_ref() else { return };
        let pa = a.profiles.as_ref().unwrap_or(pb);
        let acc = &mut self.filling[bin];
        if acc.is_empty() {
            *acc = pb.iter().map(|v| vec![0.0; v.len()]).collect();
        }
        for ((sum, va), vb) in acc.iter_mut().zip(pa).zip(pb) {
            for ((x, ya), yb) in sum.iter_mut().zip(va).zip(vb) {
                *x += ((1.0 - w) * ya + w * yb) * length;
            }
        }
        self.filling_weight[bin] += length;
    }

    /// Close the period being filled: whole when every bin saw time.
    fn close(&mut self) {
        let Some((_, sums)) = self.current.take() else { return };
        let whole = sums.time.iter().all(|&w| w > 0.0);
        if whole {
            self.done.push(sums);
        }
        for b in 0..self.bins {
            let fill = std::mem::take(&mut self.filling[b]);
            if whole && !fill.is_empty() {
                let acc = &mut self.profiles[b];
                if acc.is_empty() {
                    *acc = fill.iter().map(|v| vec![0.0; v.len()]).collect();
                }
                for (a, v) in acc.iter_mut().zip(&fill) {
                    for (x, y) in a.iter_mut().zip(v) {
                        *x += y;
                    }
                }
                self.profile_weight[b] += self.filling_weight[b];
            }
            self.filling_weight[b] = 0.0;
        }
    }

    /// Close the last period if it is complete to within rounding at time `t`.
    pub fn finish_at(&mut self, t: f64) {
        if let Some((k, _)) = &self.current {
            let end = (*k as f64 + 1.0) * self.period;
            if t >= end * (1.0 - 1e-9) {
                self.close();
            }
        }
    }

    /// Whole periods averaged.
    pub fn periods(&self) -> usize {
        self.done.len()
    }

    /// The phase average of qs in each bin (m^2/s) and its standard error over the
    /// periods (`None` with fewer than two).
    pub fn qs(&self) -> Vec<(Option<f64>, Option<f64>)> {
        (0..self.bins)
            .map(|b| {
                let means: Vec<f64> = self.done.iter().map(|p| p.qs[b] / p.time[b]).collect();
                mean_and_error(&means)
            })
            .collect()
    }

    /// The net transport per period and its error.
    pub fn net(&self) -> NetTransport {
        let per: Vec<f64> =
            self.done.iter().map(|p| p.qs.iter().sum::<f64>() * self.period / p.time.iter().sum::<f64>()).collect();
        let (mean, error) = mean_and_error(&per);
        NetTransport {
            period: self.period,
            bins: self.bins,
            spin_up_periods: self.spin_up,
            periods: self.done.len(),
            per_period: mean,
            error,
            mean_qs: mean.map(|m| m / self.period),
        }
    }

    /// Write `phases.csv`, `phase_profiles.csv` (when profiles were added) and
    /// `phases.json` into `out`, the forcing signal of each bin's centre from `forcing`.
    pub fn write(&self, out: &Path, forcing: Option<&Forcing>) -> Result<(), Error> {
        let write = |name: &str, text: String| {
            let f = out.join(name);
            std::fs::write(&f, text).map_err(|source| Error::Io { file: f, source })
        };
        let cell = |s: &mut String, x: Option<f64>| {
            if let Some(x) = x.filter(|x| x.is_finite()) {
                let _ = write!(s, "{x:.10e}");
            }
        };
        let mut text = format!("{PHASES_HEADER}\n");
        for (b, (q, e)) in self.qs().into_iter().enumerate() {
            let phase = (b as f64 + 0.5) / self.bins as f64;
            let _ = write!(text, "{b},{phase:.10e},");
            cell(&mut text, forcing.map(|f| f.value_and_rate(phase * self.period).0));
            text.push(',');
            cell(&mut text, q);
            text.push(',');
            cell(&mut text, e);
            let _ = writeln!(text, ",{}", self.done.len());
        }
        write(PHASES, text)?;
        if !self.names.is_empty() {
            let mut text = format!("phase,t_over_period,z,{}\n", self.names.join(","));
            for b in 0..self.bins {
                let w = self.profile_weight[b];
                if w.is_nan() || w <= 0.0 || self.profiles[b].is_empty() {
                    continue;
                }
                let phase = (b as f64 + 0.5) / self.bins as f64;
                for (i, z) in self.z.iter().enumerate() {
                    let _ = write!(text, "{b},{phase:.10e},{z:.10e}");
                    for col in &self.profiles[b] {
                        text.push(',');
                        cell(&mut text, col.get(i).map(|v| v / w));
                    }
                    text.push('\n');
                }
            }
            write(PHASE_PROFILES, text)?;
        }
        let net = self.net();
        let json = serde_json::to_string_pretty(&net).map_err(|e| Error::Invalid(e.to_string()))?;
        write(PHASES_SUMMARY, json + "\n")
    }
}

/// Mean and standard error of the mean (`None` for no value; no error below two).
fn mean_and_error(x: &[f64]) -> (Option<f64>, Option<f64>) {
    let n = x.len();
    if n == 0 {
        return (None, None);
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return (Some(mean), None);
    }
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (Some(mean), Some((var / n as f64).sqrt()))
}

impl Observer for PhaseAverages {
    fn start(&mut self, stepper: &dyn Stepper, _: &Clock) {
        let t = stepper.progress().time;
        let profiles = self.wants_profiles(t).then(|| stepper.phase_profiles());
        self.add(t, stepper.sample().qs, profiles);
    }

    fn step(&mut self, stepper: &dyn Stepper, progress: &Progress, _: &Clock) -> Control {
        if progress.phase == Phase::Flow {
            let t = progress.time;
            let profiles = self.wants_profiles(t).then(|| stepper.phase_profiles());
            self.add(t, stepper.sample().qs, profiles);
        }
        Control::Continue
    }

    fn finish(&mut self, stepper: &dyn Stepper, _: &super::Ending, _: &Clock) {
        self.finish_at(stepper.progress().time);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// A known sinusoid qs(t) = a + b sin(2 pi t / T + c) sampled at a fine step: each
    /// bin's average is the exact mean of the sinusoid over the bin, the net transport per
    /// period a T; noise on the samples is carried into an error that covers the truth.
    #[test]
    fn phase_averages_recover_a_sinusoid() {
        let (a, b, c, period, bins) = (0.3, 1.2, 0.7, 2.0, 16);
        let mut p = PhaseAverages::new(period, bins, 2);
        let steps_per_period = 1600;
        let dt = period / steps_per_period as f64;
        let signal = |t: f64| a + b * (TAU * t / period + c).sin();
        let mut state = 7u64;
        let mut noise = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.2
        };
        let profile =
            |t: f64| Profiles { columns: vec![("z".into(), vec![0.0, 1.0]), ("u".into(), vec![signal(t), 2.0])] };
        let periods = 12;
        for k in 0..=periods * steps_per_period {
            // each state a point sample at its own time
            let t = k as f64 * dt;
            p.add(t, Some(signal(t) + noise()), Some(profile(t)));
        }
        p.finish_at(periods as f64 * period);
        assert_eq!(p.periods(), periods - 2);
        for (bin, (q, e)) in p.qs().into_iter().enumerate() {
            let (x0, x1) = (TAU * bin as f64 / bins as f64 + c, TAU * (bin + 1) as f64 / bins as f64 + c);
            let exact = a + b * (x0.cos() - x1.cos()) / (x1 - x0);
            let (q, e) = (q.unwrap(), e.unwrap());
            assert!((q - exact).abs() < 4.0 * e + 1e-9, "bin {bin}: {q} vs {exact} +- {e}");
            assert!(e > 0.0 && e < 0.01, "bin {bin}: error {e}");
        }
        let net = p.net();
        let (m, e) = (net.per_period.unwrap(), net.error.unwrap());
        assert!((m - a * period).abs() < 4.0 * e, "{m} vs {} +- {e}", a * period);
        assert!((net.mean_qs.unwrap() - a).abs() < 4.0 * e / period);
        // without noise the profiles of each bin are the bin means (trapezoidal rule, 1e-6)
        let dir = std::env::temp_dir().join(format!("saltus-phases-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        p.write(&dir, None).unwrap();
        let text = std::fs::read_to_string(dir.join(PHASE_PROFILES)).unwrap();
        let rows: Vec<Vec<f64>> =
            text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
        assert_eq!(rows.len(), 2 * bins);
        for r in rows.iter().filter(|r| r[2] == 0.0) {
            let bin = r[0] as usize;
            let (x0, x1) = (TAU * bin as f64 / bins as f64 + c, TAU * (bin + 1) as f64 / bins as f64 + c);
            let exact = a + b * (x0.cos() - x1.cos()) / (x1 - x0);
            assert!((r[3] - exact).abs() < 1e-5, "bin {bin}: {} vs {exact}", r[3]);
        }
        let head = std::fs::read_to_string(dir.join(PHASES)).unwrap();
        assert!(head.starts_with(PHASES_HEADER));
        assert!(std::fs::read_to_string(dir.join(PHASES_SUMMARY)).unwrap().contains("\"periods\": 10"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The spin-up and an incomplete last period are left out.
    #[test]
    fn only_whole_periods_after_the_spin_up_count() {
        let mut p = PhaseAverages::new(1.0, 4, 1);
        for k in 0..=250 {
            p.add(k as f64 * 0.01, Some(1.0), None);
        }
        p.finish_at(2.5);
        assert_eq!(p.periods(), 1);
        assert!((p.net().per_period.unwrap() - 1.0).abs() < 1e-12, "{:?}", p.net());
        assert_eq!(p.net().error, None);
    }

    /// The bin means of point samples are second order in the step: halving it divides
    /// the error of every bin's mean of a sinusoid by four, at steps that do not divide
    /// the bins (the pieces are cut at the bins' edges).
    #[test]
    fn bin_means_are_second_order_in_the_step() {
        let (period, bins) = (1.0, 16);
        let signal = |t: f64| (TAU * t / period).sin();
        let error = |steps: usize| {
            let mut p = PhaseAverages::new(period, bins, 1);
            let dt = 3.0 * period / steps as f64;
            for k in 0..=steps {
                let t = k as f64 * dt;
                p.add(t, Some(signal(t)), None);
            }
            p.finish_at(3.0 * period);
            assert_eq!(p.periods(), 2);
            p.qs()
                .iter()
                .enumerate()
                .map(|(bin, (q, _))| {
                    let (x0, x1) = (TAU * bin as f64 / bins as f64, TAU * (bin + 1) as f64 / bins as f64);
                    (q.unwrap() - (x0.cos() - x1.cos()) / (x1 - x0)).abs()
                })
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (error(3 * 77), error(3 * 154));
        let order = (coarse / fine).log2();
        assert!((order - 2.0).abs() < 0.15, "order {order} ({coarse:e} -> {fine:e})");
    }
}
