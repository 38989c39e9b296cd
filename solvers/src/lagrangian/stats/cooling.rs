//! The granular temperature history of a run without fluid, against Haff's law.

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
