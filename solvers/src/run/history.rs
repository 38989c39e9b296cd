//! What a run writes while it runs, for both solvers, as one observer of the driver
//! ([`Recorder`]): the time series (`timeseries.csv`), the profile snapshots
//! (`snapshots/`), the ParaView snapshots (`vtk/`, see [`super::paraview`]) and the
//! checkpoints (`checkpoint.bin`, see [`super::checkpoint`]).
//!
//! Cadences are in simulated seconds of the flow (`output.timeseries_interval`,
//! `output.snapshot_interval`) or of the current phase (`output.checkpoint_interval`:
//! the DEM's deposition has a clock of its own). After a unit of work the driver asks
//! for a row when the flow time reached the next multiple of the interval: a solver
//! whose steps are longer than the interval (the Eulerian column once its time step has
//! grown) gives one row per step, at the step's time, and the next row is due at the next
//! multiple above it. Rows are written and flushed one at a time, so a killed run keeps
//! the rows so far. The last state is written as a row of its own at the ending.
//!
//! Nothing here is done per step: the stepper is sampled once per unit of work, and only
//! read when something is due.

use std::fs::File;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use saltus_core::scene::Scene;
use saltus_core::Error;

use super::checkpoint::{self, Cadence, Restart};
use super::paraview;
use super::{Clock, Control, Ending, Observer, Phase, Progress, Sample, Stepper};

pub use crate::output::TIMESERIES;
/// Header of the time series (`theta_g`: DEM runs without fluid, empty for the others).
pub const TIMESERIES_HEADER: &str = "t,qs,qs_star,shields,bed_surface,residual,steps,theta_g";
/// Folder of the profile snapshots.
pub const SNAPSHOTS: &str = "snapshots";
/// Index of the snapshots in [`SNAPSHOTS`]: one row per snapshot.
pub const SNAPSHOT_INDEX: &str = "index.csv";
/// Header of [`SNAPSHOT_INDEX`].
pub const SNAPSHOT_HEADER: &str = "index,t,steps,file";

/// The next multiple of `interval` strictly above `t` (a row is due there).
fn next_multiple(t: f64, interval: f64) -> f64 {
    // a time a rounding below a multiple counts as that multiple, so that rows do not come
    // in pairs one step apart
    interval * ((t / interval + 1e-9).floor() + 1.0)
}

/// A number of a row: shortest exact decimal would be longer than the profiles'
/// precision; an undefined or non-finite value is an empty cell.
fn cell(line: &mut String, x: Option<f64>) {
    use std::fmt::Write as _;
    if let Some(x) = x.and_then(crate::output::finite) {
        let _ = write!(line, "{x:.10e}");
    }
}

/// Writes the time series, the snapshots and the checkpoints of one run.
pub struct Recorder {
    dir: PathBuf,
    timeseries: Option<File>,
    index: Option<File>,
    interval: f64,
    snapshot_interval: f64,
    checkpoint_interval: f64,
    paraview_period: f64,
    /// why the first ParaView snapshot that failed was not written
    paraview_error: Option<String>,
    cadence: Cadence,
    /// resolved scene text, stored in each checkpoint
    scene: String,
    restartable: bool,
    /// the row being written (kept to reuse its buffer)
    line: String,
    error: Option<Error>,
    /// checkpoints written
    checkpoints: u64,
}

impl Recorder {
    /// Start recording `stepper`, set up from `scene`, into `dir`: `timeseries.csv` and,
    /// with snapshots, `snapshots/index.csv`, created now (so that they exist from the
    /// start of the run). A restarted run keeps the rows the checkpoint counted (read from
    /// the checkpoint's folder, which may be `dir`) and goes on with its cadences. `Err`
    /// when a file cannot be created: nothing has run yet.
    pub fn start(dir: &Path, scene: &Scene, stepper: &dyn Stepper, restart: Option<&Restart>) -> Result<Self, Error> {
        let out = &scene.output;
        let (end_time, _) = scene.end_time();
        let mut r = Self {
            dir: dir.to_path_buf(),
            timeseries: None,
            index: None,
            interval: out.timeseries_interval.unwrap_or(end_time / saltus_core::scene::TIMESERIES_ROWS),
            snapshot_interval: out.snapshot_interval,
            checkpoint_interval: out.checkpoint_interval,
            paraview_period: stepper.paraview_period(),
            paraview_error: None,
            cadence: restart.map_or_else(Cadence::default, |r| r.cadence.clone()),
            scene: scene.to_toml()?,
            restartable: stepper.restartable(),
            line: String::with_capacity(256),
            error: None,
            checkpoints: 0,
        };
        let from = restart.map(|r| r.dir.as_path());
        let rows = r.cadence.rows;
        r.timeseries =
            Some(continued(&dir.join(TIMESERIES), from.map(|d| d.join(TIMESERIES)), TIMESERIES_HEADER, rows)?);
        if r.snapshot_interval > 0.0 {
            let snaps = dir.join(SNAPSHOTS);
            std::fs::create_dir_all(&snaps).map_err(io(&snaps))?;
            let kept = r.cadence.snapshots;
            let from_index = from.map(|d| d.join(SNAPSHOTS).join(SNAPSHOT_INDEX));
            r.index = Some(continued(&snaps.join(SNAPSHOT_INDEX), from_index, SNAPSHOT_HEADER, kept)?);
            if let Some(from) = from.filter(|f| !same_dir(f, dir)) {
                for k in 0..kept {
                    let name = snapshot_name(k);
                    // a snapshot missing from the old folder is a gap, not a failure
                    let _ = std::fs::copy(from.join(SNAPSHOTS).join(&name), snaps.join(&name));
                }
            }
        }
        if restart.is_none() && stepper.progress().phase == Phase::Flow {
            // the state the flow starts from is the first row
            r.enter(Phase::Flow);
            r.sample_if_due(stepper, stepper.progress().time);
        }
        Ok(r)
    }

    /// Where the cadences are.
    pub fn cadence(&self) -> &Cadence {
        &self.cadence
    }

    /// The driver's clock the run continues from (a restart's).
    pub fn resumed_clock(&self) -> Clock {
        self.cadence.clock
    }

    /// Why a ParaView snapshot was not written (the first failure), if one was not.
    pub fn paraview_error(&self) -> Option<&str> {
        self.paraview_error.as_deref()
    }

    /// Checkpoints written so far.
    pub fn checkpoints(&self) -> u64 {
        self.checkpoints
    }

    /// The phase changed (or the run starts): the clocks of the new phase start.
    fn enter(&mut self, phase: Phase) {
        let c = &mut self.cadence;
        c.phase = Some(phase);
        c.next_checkpoint = self.checkpoint_interval;
        if phase == Phase::Flow {
            c.next_sample = 0.0;
            c.next_snapshot = self.snapshot_interval;
            c.paraview.next = 0.0;
        }
    }

    /// After a unit of work: a row, a snapshot, a ParaView snapshot, a checkpoint when due.
    pub fn after_unit(&mut self, stepper: &dyn Stepper, clock: &Clock) {
        let p = stepper.progress();
        if self.cadence.phase != Some(p.phase) {
            self.enter(p.phase);
        }
        if p.phase == Phase::Flow {
            self.sample_if_due(stepper, p.time);
            if self.snapshot_interval > 0.0 && p.time >= self.cadence.next_snapshot {
                self.snapshot(stepper, p.time, p.steps);
                self.cadence.next_snapshot = next_multiple(p.time, self.snapshot_interval);
            }
            if self.paraview_period > 0.0 && p.time >= self.cadence.paraview.next {
                let dir = paraview::folder(&self.dir);
                if let Err(e) = self.cadence.paraview.write(&dir, p.time, self.paraview_period, stepper.paraview()) {
                    // a failed snapshot does not stop the run (the report tells it)
                    self.paraview_error.get_or_insert_with(|| e.to_string());
                }
            }
        }
        if self.restartable && self.checkpoint_interval > 0.0 && p.time >= self.cadence.next_checkpoint {
            self.checkpoint(stepper, clock);
            self.cadence.next_checkpoint = next_multiple(p.time, self.checkpoint_interval);
        }
    }

    fn sample_if_due(&mut self, stepper: &dyn Stepper, time: f64) {
        if time >= self.cadence.next_sample {
            self.row(stepper.sample(), true);
            self.cadence.next_sample = next_multiple(time, self.interval);
        }
    }

    /// At the ending: a checkpoint of the state (unless it went bad: the last periodic
    /// checkpoint stays), then the last state as a row of the time series.
    pub fn at_end(&mut self, stepper: &dyn Stepper, ending: &Ending, clock: &Clock) {
        if self.restartable && !matches!(ending, Ending::Unstable(_)) {
            self.checkpoint(stepper, clock);
        }
        if stepper.progress().phase == Phase::Flow {
            let s = stepper.sample();
            if self.cadence.last_steps != Some(s.steps) {
                self.row(s, false);
            }
        }
    }

    /// The first write error of the run, if any.
    pub fn finish(self) -> Result<(), Error> {
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    fn fail(&mut self, e: Error) {
        self.error.get_or_insert(e);
    }

    /// Write one row; `on_cadence` rows are counted (and kept by a restart).
    fn row(&mut self, s: Sample, on_cadence: bool) {
        use std::fmt::Write as _;
        let line = &mut self.line;
        line.clear();
        cell(line, Some(s.time));
        for x in [s.qs, s.qs_star, s.shields, s.bed_surface, s.residual] {
            line.push(',');
            cell(line, x);
        }
        let _ = write!(line, ",{},", s.steps);
        cell(line, s.theta_g);
        line.push('\n');
        self.cadence.last_steps = Some(s.steps);
        if on_cadence {
            self.cadence.rows += 1;
        }
        if let Some(f) = self.timeseries.as_mut() {
            if let Err(e) = f.write_all(self.line.as_bytes()) {
                let file = self.dir.join(TIMESERIES);
                self.fail(Error::Io { file, source: e });
            }
        }
    }

    fn snapshot(&mut self, stepper: &dyn Stepper, time: f64, steps: u64) {
        let k = self.cadence.snapshots;
        let name = snapshot_name(k);
        let file = self.dir.join(SNAPSHOTS).join(&name);
        self.cadence.snapshots += 1;
        if let Err(e) = std::fs::write(&file, stepper.profiles().to_csv()) {
            self.fail(Error::Io { file, source: e });
            return;
        }
        let row = format!("{k},{time:.10e},{steps},{name}\n");
        if let Some(f) = self.index.as_mut() {
            if let Err(e) = f.write_all(row.as_bytes()) {
                let file = self.dir.join(SNAPSHOTS).join(SNAPSHOT_INDEX);
                self.fail(Error::Io { file, source: e });
            }
        }
    }

    fn checkpoint(&mut self, stepper: &dyn Stepper, clock: &Clock) {
        self.cadence.clock = *clock;
        let mut state = Vec::new();
        let written = stepper
            .save(&mut state)
            .map_err(|m| Error::Invalid(format!("{}: {m}", self.dir.join(checkpoint::FILE).display())))
            .and_then(|()| checkpoint::write(&self.dir, stepper.name(), &self.scene, &self.cadence, &state));
        match written {
            Ok(()) => self.checkpoints += 1,
            Err(e) => self.fail(e),
        }
    }
}

impl Observer for Recorder {
    fn step(&mut self, stepper: &dyn Stepper, _: &Progress, clock: &Clock) -> Control {
        self.after_unit(stepper, clock);
        Control::Continue
    }

    fn finish(&mut self, stepper: &dyn Stepper, ending: &Ending, clock: &Clock) {
        self.at_end(stepper, ending, clock);
    }
}

/// File name of snapshot `k`.
pub fn snapshot_name(k: u64) -> String {
    format!("profiles_{k:05}.csv")
}

fn io(file: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io { file: file.to_path_buf(), source }
}

fn same_dir(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// `file` opened for appending rows under `header`: new, or, for a restart, with the
/// header and the first `rows` rows of `from` (the same file or the old run's), so that the
/// rows the checkpoint did not count (written after it) are dropped.
fn continued(file: &Path, from: Option<PathBuf>, header: &str, rows: u64) -> Result<File, Error> {
    let mut text = String::with_capacity(header.len() + 1);
    text.push_str(header);
    text.push('\n');
    if let Some(from) = from {
        // an old file that is missing or unreadable leaves a gap before the restart, not a
        // failure: the run's state is in the checkpoint
        if let Ok(old) = std::fs::read_to_string(&from) {
            for line in old.lines().skip(1).take(rows as usize) {
                text.push_str(line);
                text.push('\n');
            }
        }
    }
    let mut f = File::create(file).map_err(io(file))?;
    f.write_all(text.as_bytes()).map_err(io(file))?;
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_due_at_the_next_multiple_above() {
        assert_eq!(next_multiple(0.0, 0.5), 0.5);
        assert_eq!(next_multiple(0.7, 0.5), 1.0);
        // a step that jumps over several multiples gives one row, the next at the multiple
        // above it
        assert_eq!(next_multiple(2.6, 0.5), 3.0);
        // a rounding below a multiple counts as the multiple
        assert_eq!(next_multiple(0.1 + 0.2 - 0.3 + 0.5 - 1e-15, 0.5), 1.0);
    }

    #[test]
    fn undefined_and_non_finite_values_are_empty_cells() {
        let mut s = String::new();
        cell(&mut s, None);
        cell(&mut s, Some(f64::NAN));
        cell(&mut s, Some(f64::INFINITY));
        assert!(s.is_empty());
        cell(&mut s, Some(0.25));
        assert_eq!(s, "2.5000000000e-1");
    }
}
