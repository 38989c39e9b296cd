//! One run driver for both solvers.
//!
//! A solver is a [`Stepper`]: it owns its state and knows how to advance it by one unit
//! of work (an accepted time step of the Eulerian column; the DEM steps up to the next
//! fluid update of the Lagrangian solver), how far it is ([`Progress`]) and what it has
//! to report ([`crate::RunReport`]). The driver ([`drive`]) owns what every solver
//! shares, in the spirit of argmin's `Executor`: the loop; the generic stops (end time,
//! step cap, wall clock: [`Limits`], read from [`Progress`] after every unit, the solver
//! only never stepping past them); the wall clock ([`Clock`]); the observers, with their
//! start, step and final hooks ([`Observer`]: the time series, snapshots, checkpoints and
//! ParaView output of [`history`], the caller's progress display and interrupt); and the
//! per-stage timing ([`timing`]). The solver ends a run only for what is its own (a
//! steady state, a breakdown). Every run ends with one [`Ending`]; a breakdown is one
//! [`Breakdown`] whichever solver met it; the last state always stays in the stepper so
//! that the caller can report it.

mod answer;
pub use answer::Answer;
pub mod checkpoint;
pub mod cpu;
pub mod history;
pub mod paraview;
pub mod phases;
pub mod start_profiles;
pub mod timing;

use std::borrow::Cow;
use std::fmt;
use std::time::Instant;

pub use timing::{Stages, Timing};

use saltus_core::param::{decimal, number};
use serde::{Deserialize, Serialize};

use crate::output::Profiles;
use crate::RunReport;

pub use history::Recorder;
pub use phases::PhaseAverages;

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
    /// the requested standard error of the answer is reached (the DEM's `target_error`)
    TargetError,
    /// the step cap is reached
    MaxSteps,
    /// the observer asked to stop (Ctrl-C, a caller's budget)
    Interrupted,
    /// the wall-clock limit of the run is reached (the state is written, with a
    /// checkpoint where the solver has them)
    WallClock,
    /// the state went bad; the stepper holds the last good state
    Unstable(Breakdown),
}

impl Ending {
    /// Short name, as written in `summary.json`.
    pub fn name(&self) -> &'static str {
        match self {
            Ending::Steady => "steady",
            Ending::EndTime => "end_time",
            Ending::TargetError => "target_error",
            Ending::MaxSteps => "max_steps",
            Ending::Interrupted => "interrupted",
            Ending::WallClock => "wall_clock",
            Ending::Unstable(_) => "unstable",
        }
    }

    /// Why the run stopped before its end, as written in `summary.json`: the breakdown or
    /// the interruption; `None` for the solver's own endings.
    pub fn error(&self) -> Option<String> {
        match self {
            Ending::Unstable(b) => Some(b.to_string()),
            Ending::Interrupted => Some("interrupted before its end".into()),
            Ending::Steady | Ending::EndTime | Ending::TargetError | Ending::MaxSteps | Ending::WallClock => None,
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
    /// steps taken in the phase
    pub steps: u64,
    /// steps counted against the step cap (the DEM's deposition and flow together)
    pub total_steps: u64,
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

/// The generic stops of a run, applied by the driver after every unit of work; a solver
/// never steps past them within a unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// end of the flow (s)
    pub end_time: f64,
    /// relative rounding within which a flow time counts as the end time: the Eulerian
    /// column cuts its last step to end at `end_time` within rounding; the DEM's time is a
    /// whole number of steps, its end exact (0)
    pub end_tolerance: f64,
    /// most steps ([`Progress::total_steps`])
    pub max_steps: u64,
    /// most wall-clock seconds of the run in this process, `None` for no limit
    pub wall: Option<f64>,
}

impl Limits {
    /// The stop `p` has reached, if any: the end time (flow phase only), then the step cap.
    pub fn reached(&self, p: &Progress) -> Option<Ending> {
        if p.phase == Phase::Flow && p.time >= self.end_time * (1.0 - self.end_tolerance) {
            Some(Ending::EndTime)
        } else if p.total_steps >= self.max_steps {
            Some(Ending::MaxSteps)
        } else {
            None
        }
    }
}

/// The driver's wall clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Clock {
    /// wall time of the run in this process (s)
    pub wall: f64,
    /// wall time of the flow phase, over restarts (s): the throughput's denominator
    pub flow: f64,
}

/// What the observer tells the driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// go on
    Continue,
    /// stop now, ending [`Ending::Interrupted`]
    Stop,
    /// stop now, ending [`Ending::TargetError`]: the answer an observer pools over several
    /// runs (seeds) has the error asked for
    Answered,
}

/// A solver as the driver sees it.
pub trait Stepper {
    /// Solver name, as in `[solver] type`.
    fn name(&self) -> &'static str;

    /// The scene's end time and step cap (the driver adds the wall clock).
    fn limits(&self) -> Limits;

    /// Advance by one unit of work, never past `limits`. `None` while the run goes on
    /// (the driver then reads the stops from [`Stepper::progress`]); the ending when the
    /// solver's own criteria end it (steady) or when the state went bad (the stepper then
    /// holds the last good state).
    fn step(&mut self, limits: &Limits) -> Option<Ending>;

    /// Where the run is.
    fn progress(&self) -> Progress;

    /// The transport rate over the averaging window found so far, for solvers that
    /// detect one (the DEM); `None` otherwise or before the window exists.
    fn answer(&self) -> Option<Answer> {
        None
    }

    /// One unit of work with the scene's limits, ending where the driver would (the end
    /// time or the step cap reached, before or by this unit): for callers that step a
    /// solver by hand.
    fn step_unit(&mut self) -> Option<Ending> {
        let limits = self.limits();
        if let Some(e) = limits.reached(&self.progress()) {
            return Some(e);
        }
        self.step(&limits).or_else(|| limits.reached(&self.progress()))
    }

    /// Profiles, summary and paragraph of the state as it is now, for a run that ended
    /// with `ending` with the driver's clock at `clock`.
    fn report(&self, ending: &Ending, clock: &Clock) -> RunReport;

    /// The state as a row of the time series (flow phase only: the driver samples
    /// nothing during set-up work).
    fn sample(&self) -> Sample;

    /// Profiles of the state as it is now, the ones [`Stepper::report`] writes: the
    /// driver's profile snapshots.
    fn profiles(&self) -> Profiles {
        self.report(&Ending::EndTime, &Clock::default()).profiles
    }

    /// Profiles of the state at this instant, which the phase averages bin: by default
    /// those of [`Stepper::profiles`]. A solver whose reported profiles are time averages
    /// (the DEM's, over its statistics window) gives here its last instantaneous fields.
    fn phase_profiles(&self) -> Profiles {
        self.profiles()
    }

    /// Wall time (s) of each stage of the solver's steps so far, in this process.
    fn stages(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }

    /// CPU time (s) the solver's own worker threads have used so far (0 for a solver that
    /// works on the calling thread only); `None` when its work runs on a pool it shares
    /// with other work, whose threads' time is not the run's alone.
    fn worker_cpu(&self) -> Option<f64> {
        Some(0.0)
    }

    /// Flow time between two ParaView snapshots (s), 0 for none.
    fn paraview_period(&self) -> f64 {
        0.0
    }

    /// The ParaView documents of the state as it is now, (name, VTK XML text) each, or why
    /// they cannot be written (a non-finite value).
    fn paraview(&self) -> Result<Vec<(&'static str, String)>, String> {
        Ok(Vec::new())
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

    /// Start from `from` (another run's final state, a neighbouring point of a sweep)
    /// instead of the scene's initial state, before the first step; `Err`, the stepper
    /// left as it was set up, for a solver that cannot or a state it cannot take.
    fn warm_start(&mut self, _from: &WarmStart) -> Result<(), String> {
        Err(format!("the {} solver cannot start from another run's state", self.name()))
    }
}

/// What a warm start starts from: another run's final state.
#[derive(Clone, Debug)]
pub enum WarmStart {
    /// its final profiles (`profiles.csv`): the Eulerian column's
    Profiles(Profiles),
    /// its final checkpoint: the DEM's grains
    State(Box<checkpoint::Restart>),
}

/// Something that watches a run: told when it starts, after every unit of work (where it
/// may stop the run) and at its ending, each time with the stepper, its progress and the
/// driver's clock.
pub trait Observer {
    /// Before the first unit of work.
    fn start(&mut self, _stepper: &dyn Stepper, _clock: &Clock) {}

    /// After every unit of work.
    fn step(&mut self, stepper: &dyn Stepper, progress: &Progress, clock: &Clock) -> Control;

    /// At the ending, with the last state.
    fn finish(&mut self, _stepper: &dyn Stepper, _ending: &Ending, _clock: &Clock) {}
}

/// A closure of the progress is an observer of every unit of work (a progress display, an
/// interrupt, a caller's budget); it also sees the final progress.
impl<F: FnMut(&Progress) -> Control> Observer for F {
    fn step(&mut self, _: &dyn Stepper, progress: &Progress, _: &Clock) -> Control {
        self(progress)
    }
    fn finish(&mut self, stepper: &dyn Stepper, _: &Ending, _: &Clock) {
        // a bar or a log ends where the run did
        self(&stepper.progress());
    }
}

/// An observer that never stops a run.
pub struct Quiet;

impl Observer for Quiet {
    fn step(&mut self, _: &dyn Stepper, _: &Progress, _: &Clock) -> Control {
        Control::Continue
    }
}

/// How a driven run ended.
#[derive(Clone, Debug)]
pub struct Driven {
    /// why it stopped
    pub ending: Ending,
    /// the driver's clock at the ending
    pub clock: Clock,
    /// wall time the observers took (s)
    pub output: f64,
}

impl Driven {
    /// The run's timing: the solver's stages, the observers' output and the rest.
    pub fn timing(&self, stepper: &dyn Stepper) -> Timing {
        Timing::new(self.clock.wall, stepper.stages().into_iter(), self.output)
    }
}

/// Drive `stepper` until it ends or `observer` stops it; the stepper keeps its last state.
pub fn drive(stepper: &mut dyn Stepper, observer: &mut dyn Observer) -> Driven {
    drive_with(stepper, &mut [observer], None, Clock::default())
}

/// [`drive`] with several observers (called in order; the first that asks to stop ends the
/// run after the others saw the unit), a wall-clock limit (s) and the clock a restarted
/// run continues from.
pub fn drive_with(
    stepper: &mut dyn Stepper,
    observers: &mut [&mut dyn Observer],
    wall_limit: Option<f64>,
    resumed: Clock,
) -> Driven {
    let start = Instant::now();
    let mut limits = stepper.limits();
    limits.wall = wall_limit;
    let mut output = 0.0;
    let mut clock = Clock { wall: 0.0, flow: resumed.flow };
    let mut flow_started: Option<(Instant, f64)> = None;
    let tick = |clock: &mut Clock, phase: Phase, flow_started: &mut Option<(Instant, f64)>| {
        clock.wall = start.elapsed().as_secs_f64();
        if phase == Phase::Flow {
            let (t0, before) = *flow_started.get_or_insert((Instant::now(), clock.flow));
            clock.flow = before + t0.elapsed().as_secs_f64();
        }
    };
    let t = Instant::now();
    for o in observers.iter_mut() {
        o.start(stepper, &clock);
    }
    output += t.elapsed().as_secs_f64();
    let ending = loop {
        let p = stepper.progress();
        if let Some(e) = limits.reached(&p) {
            break e;
        }
        if limits.wall.is_some_and(|w| start.elapsed().as_secs_f64() >= w) {
            break Ending::WallClock;
        }
        if p.phase == Phase::Flow {
            flow_started.get_or_insert((Instant::now(), clock.flow));
        }
        let own = stepper.step(&limits);
        let p = stepper.progress();
        tick(&mut clock, p.phase, &mut flow_started);
        if let Some(e) = own {
            break e;
        }
        let t = Instant::now();
        let (mut stop, mut answered) = (false, false);
        for o in observers.iter_mut() {
            match o.step(stepper, &p, &clock) {
                Control::Continue => {}
                Control::Stop => stop = true,
                Control::Answered => answered = true,
            }
        }
        output += t.elapsed().as_secs_f64();
        if stop {
            break Ending::Interrupted;
        }
        if answered {
            break Ending::TargetError;
        }
    };
    tick(&mut clock, stepper.progress().phase, &mut flow_started);
    let t = Instant::now();
    for o in observers.iter_mut() {
        o.finish(stepper, &ending, &clock);
    }
    output += t.elapsed().as_secs_f64();
    clock.wall = start.elapsed().as_secs_f64();
    Driven { ending, clock, output }
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
        fn limits(&self) -> Limits {
            Limits { end_time: self.end as f64, end_tolerance: 0.0, max_steps: 7, wall: None }
        }
        fn step(&mut self, _: &Limits) -> Option<Ending> {
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
            None
        }
        fn progress(&self) -> Progress {
            Progress {
                phase: Phase::Flow,
                time: self.n as f64,
                end_time: self.end as f64,
                steps: self.n,
                total_steps: self.n,
                dt: 1.0,
                residual: None,
            }
        }
        fn sample(&self) -> Sample {
            Sample { time: self.n as f64, steps: self.n, ..Sample::default() }
        }
        fn report(&self, ending: &Ending, _: &Clock) -> RunReport {
            RunReport {
                profiles: Profiles::default(),
                summary: Summary::default(),
                text: format!("{} after {}", ending.name(), self.n),
            }
        }
    }

    #[test]
    fn the_driver_stops_on_the_end_the_cap_a_breakdown_and_the_observer() {
        let mut c = Counter { n: 0, end: 5, bad: None };
        let d = drive(&mut c, &mut Quiet);
        assert_eq!((&d.ending, c.n), (&Ending::EndTime, 5));

        // the step cap (7) comes before an end time of 10
        let mut c = Counter { n: 0, end: 10, bad: None };
        let d = drive(&mut c, &mut Quiet);
        assert_eq!((&d.ending, c.n), (&Ending::MaxSteps, 7));

        let mut c = Counter { n: 0, end: 5, bad: Some(4) };
        let d = drive(&mut c, &mut Quiet);
        assert_eq!(c.n, 3, "the last good state is kept");
        let b = d.ending.breakdown().expect("a breakdown");
        assert_eq!(b.to_string(), "t = 3.000000 s: phi = NaN in cell 3 (z = 0.500000 m): not finite");

        let mut c = Counter { n: 0, end: 10, bad: None };
        let mut seen = Vec::new();
        let mut stop_at_three = |p: &Progress| {
            seen.push(p.steps);
            if p.steps >= 3 {
                Control::Stop
            } else {
                Control::Continue
            }
        };
        let d = drive(&mut c, &mut stop_at_three);
        assert_eq!((d.ending.name(), c.n), ("interrupted", 3));
        // every unit, then the final state once more
        assert_eq!(seen, [1, 2, 3, 3]);

        // no time left: the wall-clock stop comes before any unit
        let mut c = Counter { n: 0, end: 10, bad: None };
        let d = drive_with(&mut c, &mut [&mut Quiet], Some(0.0), Clock::default());
        assert_eq!((&d.ending, c.n), (&Ending::WallClock, 0));
        let sum: f64 = d.timing(&c).stages.values().sum();
        assert!((sum - d.clock.wall).abs() <= 1e-12 * d.clock.wall.max(1.0), "{sum} {:?}", d.clock);
    }
}
