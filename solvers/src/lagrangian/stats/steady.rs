//! The steady-state test on the transport rate.

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
