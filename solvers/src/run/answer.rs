//! What a run has measured so far, for observers that pool several runs.

/// The run's answer so far: the transport rate over the averaging window the run found in
/// its own series ([`super::Stepper::answer`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Answer {
    /// start of the window (s)
    pub start: f64,
    /// the transport rate qs over it (m^2/s)
    pub mean: f64,
    /// its standard error from the window's blocks (m^2/s), when there are enough
    pub stderr: Option<f64>,
    /// Geweke's z between the window's first 10 % and last 50 %, when tested
    pub geweke_z: Option<f64>,
}
