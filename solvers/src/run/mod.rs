//! One run driver for both solvers.
//!
//! A solver is a [`Stepper`]: it owns its state and knows how to advance it by one unit
//! of work (an accepted time step of the Eulerian column; the DEM steps up to the next
//! fluid update of the Lagrangian solver), how far it is ([`Progress`]) and what it has
//! to report ([`crate::RunReport`]). The driver ([`drive`]) owns the loop, the wall
//! clock and the observer, in the spirit of argmin's `Executor`: it stops the run on the
//! solver's own ending, on a breakdown or when the observer asks, and always leaves the
//! last state in the stepper so that the caller can report it. Every run ends with one
//! [`Ending`]; a breakdown is one [`Breakdown`] whichever solver met it.

pub mod checkpoint;
pub mod history;

use std::borrow::Cow;
use std::fmt;
use std::path::Path;
use std::time::Instant;

use saltus_core::param::{decimal, number};
use serde::{Deserialize, Serialize};

use crate::output::Profiles;
use crate::RunReport;

pub use history::Recorder;

/// Where a run went bad.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Place {
    /// a cell of the column, by index from the bottom, with its centre (m)
    Cell {
        /// index from the bottom
        index: usize,
        /// cell centre (m)
        z: f64,
    },
    /// a particle, by index
    Particle {
        /// index in the particle arrays
        index: usize,
    },
    /// the column as a whole (a linear system, a global constraint)
    Column,
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Cell { index, z } => write!(f, "cell {index} (z = {} m)", decimal(*z)),
            Place::Particle { index } => write!(f, "particle {index}"),
            Place::Column => f.write_str("the column"),
        }
    }
}

/// Where and why a run stopped: time, place, field, value and reason.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Breakdown {
    /// simulated time (s)
    pub time: f64,
    /// where
    pub place: Place,
    /// the field that went bad (`phi`, `u_f`, `velocity`, ...)
    pub field: Cow<'static, str>,
    /// its value
    pub value: f64,
    /// what is wrong
    pub reason: String,
}

impl fmt::Display for Breakdown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "t = {} s: {} = {} in {}: {}",
            decimal(self.time),
            self.field,
            number(self.value),
            self.place,
            self.reason
        )
    }
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Ending {
    /// the solver's steady-state criterion is met
    Steady,
    /// the end time is reached
    EndTime,
    /// the step cap is reached
    MaxSteps,
    /// the observer asked to stop (Ctrl-C, a caller's budget)
    Interrupted,
    /// the state went bad; the stepper holds the last good state
    Unstable(Breakdown),
}

impl Ending {
    /// Short name, as written in `summary.json`.
    pub fn name(&self) -> &'static str {
        match self {
            Ending::Steady => "steady",
            Ending::EndTime => "end_time",
            Ending::MaxSteps => "max_steps",
            Ending::Interrupted => "interrupted",
            Ending::Unstable(_) => "unstable",
        }
    }

    /// Why the run stopped before its end, as written in `summary.json`: the breakdown or
    /// the interruption; `None` for the solver's own endings.
    pub fn error(&self) -> Option<String> {
        match self {
            Ending::Unstable(b) => Some(b.to_string()),
            Ending::Interrupted => Some("interrupted before its end".into()),
            Ending::Steady | Ending::EndTime | Ending::MaxSteps => None,
        }
    }

    /// The breakdown, for an unstable run.
    pub fn breakdown(&self) -> Option<&Breakdown> {
        match self {
            Ending::Unstable(b) => Some(b),
            _ => None,
        }
    }
}

/// What the solver is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// set-up work before the flow (the DEM deposition)
    Setup,
    /// the flow
    Flow,
}

/// How far a run is, handed to the observer after every unit of work.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Progress {
    /// what the solver is doing
    pub phase: Phase,
    /// simulated time of the phase (s)
    pub time: f64,
    /// end time of the phase (s)
    pub end_time: f64,
    /// steps taken
    pub steps: u64,
    /// current time step (s)
    pub dt: f64,
    /// steady-state residual in the solver's own measure (1/s for the Eulerian rates, a
    /// relative change of the transport rate between windows for the DEM); `None` before
    /// the solver has one
    pub residual: Option<f64>,
}

/// The state of a run as one row of `timeseries.csv`, read without advancing anything.
/// A figure the state does not define (no transport measured yet, no density contrast)
/// is `None` and written as an empty cell.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// simulated time of the flow (s)
    pub time: f64,
    /// transport rate per unit width (m^2/s), of the state as it is (not time-averaged)
    pub qs: Option<f64>,
    /// qs / sqrt((s - 1) g d^3)
    pub qs_star: Option<f64>,
    /// largest fluid shear stress over (rho_p - rho_f) g d
    pub shields: Option<f64>,
    /// level below which 1 % of qs flows (m)
    pub bed_surface: Option<f64>,
    /// the solver's steady-state residual ([`Progress::residual`])
    pub residual: Option<f64>,
    /// steps of the flow
    pub steps: u64,
    /// granular temperature of the mobile particles (m^2/s^2), for a DEM run without
    /// fluid, where it is the history to report instead of transport
    pub theta_g: Option<f64>,
}

/// What the observer tells the driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// go on
    Continue,
    /// stop now, ending [`Ending::Interrupted`]
    Stop,
}

/// A solver as the driver sees it.
pub trait Stepper {
    /// Solver name, as in `[solver] type`.
    fn name(&self) -> &'static str;

    /// Advance by one unit of work. `None` while the run goes on; the ending when the
    /// solver's own criteria end it (steady, end time, step cap) or when the state went
    /// bad (the stepper then holds the last good state).
    fn step(&mut self) -> Option<Ending>;

    /// Where the run is.
    fn progress(&self) -> Progress;

    /// Profiles, summary and paragraph of the state as it is now, for a run that ended
    /// with `ending` after `wall` seconds of wall-clock time.
    fn report(&self, ending: &Ending, wall: f64) -> RunReport;

    /// Where the run's outputs go, for a solver that writes some during the run (the
    /// DEM's VTK snapshots); told once before the first step. An extension of the
    /// argmin-like loop: the solver's own files belong to the solver, their folder to
    /// the caller.
    fn set_output_dir(&mut self, _dir: &Path) {}

    /// The state as a row of the time series (flow phase only: the driver samples
    /// nothing during set-up work).
    fn sample(&self) -> Sample;

    /// Profiles of the state as it is now, the ones [`Stepper::report`] writes: the
    /// driver's profile snapshots.
    fn profiles(&self) -> Profiles {
        self.report(&Ending::EndTime, 0.0).profiles
    }

    /// Append to `out` everything a continuation needs to go on bit for bit from the state
    /// as it is now ([`Stepper::restore`]); `Err` for a solver without restart.
    fn save(&self, _out: &mut Vec<u8>) -> Result<(), String> {
        Err(format!("the {} solver writes no checkpoint", self.name()))
    }

    /// Take the state [`Stepper::save`] wrote, in a stepper set up from the same scene.
    fn restore(&mut self, _state: &[u8]) -> Result<(), String> {
        Err(format!("the {} solver cannot restart from a checkpoint", self.name()))
    }

    /// Whether [`Stepper::save`] and [`Stepper::restore`] work.
    fn restartable(&self) -> bool {
        false
    }

    /// Start from `profiles` (another run's final profiles, a neighbouring point of a
    /// sweep) instead of the scene's initial state, before the first step; `Err` for a
    /// solver that cannot.
    fn warm_start(&mut self, _profiles: &Profiles) -> Result<(), String> {
        Err(format!("the {} solver cannot start from another run's profiles", self.name()))
    }
}

/// Something that watches a run.
pub trait Observer {
    /// Called after every unit of work.
    fn observe(&mut self, progress: &Progress) -> Control;
}

impl<F: FnMut(&Progress) -> Control> Observer for F {
    fn observe(&mut self, progress: &Progress) -> Control {
        self(progress)
    }
}

/// An observer that never stops a run.
pub struct Quiet;

impl Observer for Quiet {
    fn observe(&mut self, _: &Progress) -> Control {
        Control::Continue
    }
}

/// Drive `stepper` until it ends or `observer` stops it. Returns the ending and the
/// wall-clock time (s); the stepper keeps its last state.
pub fn drive(stepper: &mut dyn Stepper, observer: &mut dyn Observer) -> (Ending, f64) {
    drive_recorded(stepper, observer, None)
}

/// [`drive`], with `recorder` (when given) sampling the time series, the snapshots and
/// the checkpoints after every unit of work at their cadence, and the last state at the
/// ending. The recorder keeps its first write error for the caller
/// ([`Recorder::finish`]): a full disk does not stop a long run.
pub fn drive_recorded(
    stepper: &mut dyn Stepper,
    observer: &mut dyn Observer,
    mut recorder: Option<&mut Recorder>,
) -> (Ending, f64) {
    let start = Instant::now();
    let ending = loop {
        if let Some(e) = stepper.step() {
            // the observer sees the final state too, so a bar or a log ends where the run did
            observer.observe(&stepper.progress());
            break e;
        }
        if let Some(r) = recorder.as_deref_mut() {
            r.after_unit(stepper);
        }
        if observer.observe(&stepper.progress()) == Control::Stop {
            break Ending::Interrupted;
        }
    };
    if let Some(r) = recorder {
        r.at_end(stepper, &ending);
    }
    (ending, start.elapsed().as_secs_f64())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::Summary;

    /// Counts to `n` and ends at the end time, or breaks down at `bad`.
    struct Counter {
        n: u64,
        end: u64,
        bad: Option<u64>,
    }

    impl Stepper for Counter {
        fn name(&self) -> &'static str {
            "counter"
        }
        fn step(&mut self) -> Option<Ending> {
            if Some(self.n + 1) == self.bad {
                return Some(Ending::Unstable(Breakdown {
                    time: self.n as f64,
                    place: Place::Cell { index: 3, z: 0.5 },
                    field: "phi".into(),
                    value: f64::NAN,
                    reason: "not finite".into(),
                }));
            }
            self.n += 1;
            (self.n >= self.end).then_some(Ending::EndTime)
        }
        fn progress(&self) -> Progress {
            Progress {
                phase: Phase::Flow,
                time: self.n as f64,
                end_time: self.end as f64,
                steps: self.n,
                dt: 1.0,
                residual: None,
            }
        }
        fn sample(&self) -> Sample {
            Sample { time: self.n as f64, steps: self.n, ..Sample::default() }
        }
        fn report(&self, ending: &Ending, _: f64) -> RunReport {
            RunReport {
                profiles: Profiles::default(),
                summary: Summary::default(),
                text: format!("{} after {}", ending.name(), self.n),
            }
        }
    }

    #[test]
    fn the_driver_stops_on_the_end_on_a_breakdown_and_on_the_observer() {
        let mut c = Counter { n: 0, end: 10, bad: None };
        let (e, _) = drive(&mut c, &mut Quiet);
        assert_eq!((e, c.n), (Ending::EndTime, 10));

        let mut c = Counter { n: 0, end: 10, bad: Some(4) };
        let (e, _) = drive(&mut c, &mut Quiet);
        assert_eq!(c.n, 3, "the last good state is kept");
        let b = e.breakdown().expect("a breakdown");
        assert_eq!(b.to_string(), "t = 3.000000 s: phi = NaN in cell 3 (z = 0.500000 m): not finite");

        let mut c = Counter { n: 0, end: 10, bad: None };
        let mut seen = 0;
        let mut stop_at_five = |p: &Progress| {
            seen += 1;
            if p.steps >= 5 {
                Control::Stop
            } else {
                Control::Continue
            }
        };
        let (e, _) = drive(&mut c, &mut stop_at_five);
        assert_eq!((e.name(), c.n, seen), ("interrupted", 5, 5));
    }
}
