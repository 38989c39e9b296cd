//! # saltus-solvers
//!
//! Solvers of saltus: `eulerian` ([`eulerian`], the two-fluid column of Chassagne et al.
//! 2023) and `lagrangian` ([`lagrangian`], soft-sphere DEM coupled to the column, Maurin
//! et al. 2015). [`mod@column`] is the fluid column shared by both. [`resolve`] turns a
//! scene into its solver, the only place that dispatches on the solver type; [`run()`]
//! drives it ([`run::drive`]) and writes its outputs.

// Errors carry file, key and message for the user; they are built once per failed run,
// never in a hot loop, so their size does not matter.
#![allow(clippy::result_large_err)]

pub mod column;
pub mod eulerian;
pub mod inputs;
pub mod lagrangian;
pub mod output;
pub mod run;
pub mod validate;

use std::fmt;
use std::path::Path;

use saltus_core::scene::{Scene, SolverKind};
use saltus_core::Error;

pub use output::{Profiles, Summary};
pub use run::{Ending, Observer, Progress, Stepper};
pub use validate::validate;

/// Result of a run: what was written, and a paragraph for the terminal.
#[derive(Clone, Debug, Default)]
pub struct RunReport {
    /// profiles at the end of the run
    pub profiles: Profiles,
    /// the summary written to `summary.json`
    pub summary: Summary,
    /// one paragraph
    pub text: String,
}

impl fmt::Display for RunReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// How a run ended, with the last state: returned on every ending, after the outputs
/// are written.
#[derive(Clone, Debug)]
pub struct RunOutcome {
    /// why the run stopped
    pub ending: Ending,
    /// profiles, summary and paragraph of the last state (as written)
    pub report: RunReport,
    /// wall-clock time of the run (s)
    pub wall: f64,
}

/// The solver of `scene`, set up and ready to step. The only dispatch on the solver type.
pub fn resolve(scene: &Scene) -> Result<Box<dyn Stepper + '_>, Error> {
    Ok(match scene.solver.kind {
        SolverKind::Eulerian => {
            let cfg = eulerian::Config::from_scene(scene)?;
            Box::new(eulerian::Eulerian::new(scene, cfg)?)
        }
        SolverKind::Lagrangian => {
            let cfg = lagrangian::Config::from_scene(scene)?;
            Box::new(lagrangian::Lagrangian::new(scene, cfg)?)
        }
    })
}

/// Run `scene`, writing its outputs into `out`. `observer` sees every unit of work and
/// may stop the run ([`Ending::Interrupted`]). Every ending, an unstable one included,
/// writes the last state and returns it; `Err` only when the scene cannot be set up or
/// the outputs cannot be written.
pub fn run(scene: &Scene, out: &Path, observer: &mut dyn Observer) -> Result<RunOutcome, Error> {
    let mut stepper = resolve(scene)?;
    // a folder that cannot be made fails before the work, not after it
    std::fs::create_dir_all(out).map_err(|source| Error::Io { file: out.to_path_buf(), source })?;
    stepper.set_output_dir(out);
    let (ending, wall) = run::drive(stepper.as_mut(), observer);
    let report = stepper.report(&ending, wall);
    output::write_run(out, scene, &report.profiles, &report.summary)?;
    Ok(RunOutcome { ending, report, wall })
}
