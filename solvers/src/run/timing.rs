//! Wall time per stage of a run, counted by the solvers and the driver and written to
//! `summary.json` (`timing`) and the run's closing paragraph.
//!
//! A stage is timed by reading the clock at its start and end (`Instant`, a vDSO call of
//! a few tens of nanoseconds); the DEM reads it a few times per step, the Eulerian column
//! a few times per attempt, so the counting costs well under 1 % of a step. The times
//! are those of this process: a restarted run counts from its restart.

use std::time::Instant;

pub use crate::output::Timing;

/// Running wall times of a fixed list of stages.
#[derive(Clone, Debug)]
pub struct Stages {
    names: &'static [&'static str],
    secs: Vec<f64>,
}

impl Default for Stages {
    fn default() -> Self {
        Self::new(&[])
    }
}

impl Stages {
    /// Zero time in each of `names`.
    pub fn new(names: &'static [&'static str]) -> Self {
        Self { names, secs: vec![0.0; names.len()] }
    }

    /// Add the time since `since` to stage `k`; the end of this stage, for the next one to
    /// start from.
    #[inline]
    pub fn lap(&mut self, k: usize, since: Instant) -> Instant {
        let now = Instant::now();
        if let Some(s) = self.secs.get_mut(k) {
            *s += now.duration_since(since).as_secs_f64();
        }
        now
    }

    /// Add `secs` to stage `k`.
    pub fn add(&mut self, k: usize, secs: f64) {
        if let Some(s) = self.secs.get_mut(k) {
            *s += secs;
        }
    }

    /// (name, seconds) of every stage, in order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.names.iter().copied().zip(self.secs.iter().copied())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stages_and_the_rest_add_up_to_the_wall_time() {
        let mut s = Stages::new(&["a", "b"]);
        s.add(0, 1.5);
        s.add(1, 0.25);
        s.add(7, 3.0);
        let t = Timing::new(2.0, s.iter(), 0.125);
        let sum: f64 = t.stages.values().sum();
        assert_eq!(sum, 2.0);
        assert_eq!(t.stages["other"], 0.125);
        assert!(t.line().starts_with("wall time 2.000 s: a 1.500 s (75.0 %)"), "{}", t.line());
        // more counted than the wall clock saw (rounding): nothing negative
        assert_eq!(Timing::new(1.0, s.iter(), 0.0).stages["other"], 0.0);
    }
}
