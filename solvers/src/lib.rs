//! # saltus-solvers
//!
//! Solvers of saltus. The entry point [`run`] dispatches on the scene's `[solver] type`:
//! `eulerian` ([`eulerian`], the two-fluid column of Chassagne et al. 2023) and
//! `lagrangian` ([`lagrangian`], soft-sphere DEM coupled to the column, Maurin et al.
//! 2015). [`mod@column`] is the fluid column shared by both.

// Errors carry file, key and message for the user; they are built once per failed run,
// never in a hot loop, so their size does not matter.
#![allow(clippy::result_large_err)]

pub mod column;
pub mod eulerian;
pub mod lagrangian;
pub mod output;
pub mod run;
pub mod validate;

use std::fmt;
use std::path::Path;
use std::time::Instant;

use saltus_core::scene::Scene;
use saltus_core::Error;

pub use eulerian::Progress;
pub use output::{Profiles, Summary};
pub use validate::validate;

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
    let start = Instant::now();
    let ending = model.run(observer);
    let wall = start.elapsed().as_secs_f64();
    let report = eulerian_report(scene, &mut model, &ending, wall);
    output::write_run(out, scene, &report.profiles, &report.summary)?;
    if let eulerian::Ending::Unstable(b) = ending {
        return Err(Error::Invalid(format!(
            "{}: run stopped, unstable at {b}; the state at t = {:.6} s is written to {}",
            scene.path.display(),
            model.time(),
            out.display()
        )));
    }
    Ok(report)
}

/// Profiles, summary and paragraph of an Eulerian run.
pub fn eulerian_report(
    scene: &Scene,
    m: &mut eulerian::Eulerian<'_>,
    ending: &eulerian::Ending,
    wall: f64,
) -> RunReport {
    let derived = m.derived();
    let mut p = Profiles::default();
    p.push("z", m.z().to_vec());
    p.push("phi", m.phi().to_vec());
    p.push("u_f", m.u_f().to_vec());
    p.push("u_p", m.u_p().to_vec());
    if m.is_kinetic() {
        p.push("theta_g", m.temperature().to_vec());
    }
    p.push("w_p", derived.w_p.clone());
    p.push("p_p", derived.p_p.clone());
    p.push("tau_p", derived.tau_p.clone());
    p.push("tau_f", derived.tau_f.clone());
    p.push("nu_t", m.eddy_viscosity().to_vec());
    if let Some((k, omega)) = m.k_omega() {
        p.push("k", k.to_vec());
        p.push("omega", omega.to_vec());
    }
    let q: Vec<f64> = m.phi().iter().zip(m.u_p()).map(|(a, b)| a.max(0.0) * b).collect();
    p.push("q_s", q.clone());
    p.push(if m.is_kinetic() { "inertial_number" } else { "control_number" }, derived.control.clone());

    let qs: f64 = q.iter().zip(m.dz()).map(|(q, h)| q * h).sum();
    let tau_max = derived.tau_f.iter().fold(0.0f64, |a, t| a.max(t.abs()));
    let scales = output::TransportScales::new(
        scene,
        scene.particles.density,
        scene.particles.diameter,
        m.config().domain.water_depth,
    );
    let (z1, z99) = output::flux_levels(m.faces(), &q, 0.01, 0.99);
    let (ending_name, error) = match ending {
        eulerian::Ending::Steady => ("steady", None),
        eulerian::Ending::EndTime => ("end_time", None),
        eulerian::Ending::MaxSteps => ("max_steps", None),
        eulerian::Ending::Unstable(b) => ("unstable", Some(b.to_string())),
    };
    let summary = Summary {
        scene: scene.meta.name.clone(),
        solver: "eulerian".into(),
        qs,
        qs_star: scales.qs_star(qs),
        shields: scales.shields(tau_max),
        shields_nominal: scales.shields_nominal,
        bed_height: z1,
        transport_layer_thickness: z99 - z1,
        steady: matches!(ending, eulerian::Ending::Steady),
        ending: ending_name.into(),
        sim_time_s: m.time(),
        steps: m.steps(),
        rejected_steps: Some(m.rejected_steps()),
        wall_time_s: wall,
        mass_error: Some(m.mass_error()),
        residual: m.residual(),
        cells: m.len(),
        error,
        particles: None,
        particle_steps_per_s: None,
        shields_turbulent: None,
    };
    // a column without moving grains (clear water) has no transport levels
    let layers = if z1.is_finite() && summary.transport_layer_thickness.is_finite() {
        format!("bed surface {z1:.4} m, transport layer {:.4} m", summary.transport_layer_thickness)
    } else {
        "no sediment transport".to_string()
    };
    let text = format!(
        "{}: {} after {:.3} s simulated ({} steps, {} rejected) in {:.3} s wall time; qs* = {:.4} (qs = {:.4e} m^2/s), Shields {:.3}, {layers}, mass error {:.1e}",
        scene.meta.name,
        if summary.steady { "steady" } else { ending_name },
        summary.sim_time_s,
        summary.steps,
        m.rejected_steps(),
        wall,
        summary.qs_star,
        qs,
        summary.shields,
        m.mass_error()
    );
    RunReport { profiles: p, summary, text }
}
