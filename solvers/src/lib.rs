//! # saltus-solvers
//!
//! Solvers of saltus. The entry point [`run()`] dispatches on the scene's `[solver] type`:
//! `eulerian` ([`eulerian`], the two-fluid column of Chassagne et al. 2023) and
//! `lagrangian` ([`lagrangian`], soft-sphere DEM coupled to the column, Maurin et al.
//! 2015). [`mod@column`] is the fluid column shared by both.

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

use saltus_core::scene::Scene;
use saltus_core::Error;

pub use output::{Profiles, Summary};
pub use validate::validate;

/// Progress record of the legacy observer of [`run()`] (the driver's is
/// [`run::Progress`]); kept until the Lagrangian solver implements [`run::Stepper`].
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    /// simulated time (s)
    pub time: f64,
    /// end time (s)
    pub end_time: f64,
    /// accepted steps
    pub steps: usize,
    /// current time step (s)
    pub dt: f64,
    /// steady residual
    pub residual: f64,
}

/// Solvers the program knows, with whether this build implements them.
pub const SOLVERS: [(&str, bool); 2] = [("eulerian", true), ("lagrangian", true)];

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

/// Name of the scene's solver (`[solver] type`, checked when the scene was loaded).
pub fn solver_name(scene: &Scene) -> Result<&str, Error> {
    Ok(scene.solver.kind.name())
}

/// Run `scene`, writing its outputs into `out`. `observer` sees every accepted step and
/// may stop the run by returning `false`. A run that breaks down writes the last good
/// state and a summary carrying the error, then returns the error.
pub fn run(scene: &Scene, out: &Path, observer: &mut dyn FnMut(&Progress) -> bool) -> Result<RunReport, Error> {
    if solver_name(scene)? == "lagrangian" {
        return lagrangian::run(scene, out, observer);
    }
    let cfg = eulerian::Config::from_scene(scene)?;
    let mut model = eulerian::Eulerian::new(scene, cfg)?;
    let mut legacy = |p: &run::Progress| {
        let go_on = observer(&Progress {
            time: p.time,
            end_time: p.end_time,
            steps: p.steps as usize,
            dt: p.dt,
            residual: p.residual.unwrap_or(f64::INFINITY),
        });
        if go_on {
            run::Control::Continue
        } else {
            run::Control::Stop
        }
    };
    let (ending, wall) = run::drive(&mut model, &mut legacy);
    let report = run::Stepper::report(&model, &ending, wall);
    output::write_run(out, scene, &report.profiles, &report.summary)?;
    if let run::Ending::Unstable(b) = ending {
        return Err(Error::Invalid(format!(
            "{}: run stopped, unstable at {b}; the state at t = {:.6} s is written to {}",
            scene.path.display(),
            model.time(),
            out.display()
        )));
    }
    Ok(report)
}
