//! `saltus run`: one scene through its solver, with progress on stderr and the profile
//! figure next to the solver's outputs.

use std::path::Path;
use std::time::Instant;

use saltus_core::scene::Scene;
use saltus_solvers::{Progress, RunReport};

/// Run `scene` into `out`; with `progress`, a status line on stderr a few times a second.
pub fn run_scene(scene: &Scene, out: &Path, progress: bool) -> anyhow::Result<RunReport> {
    let mut last = Instant::now();
    let mut observer = |p: &Progress| {
        if progress && last.elapsed().as_millis() > 200 {
            last = Instant::now();
            eprint!(
                "\r  t = {:9.3} / {:.0} s  step {:8}  dt = {:.2e} s  residual {:.2e} /s   ",
                p.time, p.end_time, p.steps, p.dt, p.residual
            );
        }
        true
    };
    let result = saltus_solvers::run(scene, out, &mut observer);
    if progress {
        eprint!("\r{:100}\r", "");
    }
    Ok(result?)
}
