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
pub mod lagrangian;
pub mod output;
pub mod run;

use std::fmt;
use std::path::Path;

use saltus_core::scene::Scene;
use saltus_core::Error;

pub use output::{Profiles, Summary};
pub use run::{Ending, Observer, Progress, Stepper};

/// The solvers of `[solver] type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solver {
    /// the two-fluid column ([`eulerian`])
    Eulerian,
    /// the DEM coupled to the column ([`lagrangian`])
    Lagrangian,
}

impl Solver {
    /// Every solver, in the order the help lists them.
    pub const ALL: [Solver; 2] = [Solver::Eulerian, Solver::Lagrangian];

    /// Name, as in `[solver] type`.
    pub fn name(self) -> &'static str {
        match self {
            Solver::Eulerian => "eulerian",
            Solver::Lagrangian => "lagrangian",
        }
    }

    /// The solver `scene` asks for.
    pub fn of(scene: &Scene) -> Result<Self, Error> {
        let file = scene.path.display();
        let known = || Solver::ALL.map(Solver::name).join(", ");
        let name =
            scene.solver.as_ref().and_then(|t| t.get("type")).and_then(|v| v.as_str()).ok_or_else(|| {
                Error::Invalid(format!("{file}: key `solver.type`: missing; known solvers: {}", known()))
            })?;
        Solver::ALL.into_iter().find(|s| s.name() == name).ok_or_else(|| {
            Error::Invalid(format!("{file}: key `solver.type`: unknown solver `{name}`; known: {}", known()))
        })
    }
}

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
    Ok(match Solver::of(scene)? {
        Solver::Eulerian => {
            let cfg = eulerian::Config::from_scene(scene)?;
            Box::new(run::interim::EulerianRun::new(scene, eulerian::Eulerian::new(scene, cfg)?))
        }
        Solver::Lagrangian => {
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

/// Profiles, summary and paragraph of an Eulerian run.
pub fn eulerian_report(scene: &Scene, m: &mut eulerian::Eulerian<'_>, ending: &Ending, wall: f64) -> RunReport {
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
    let ending_name = ending.name();
    let summary = Summary {
        scene: scene.meta.name.clone(),
        solver: "eulerian".into(),
        qs: Some(qs),
        qs_star: output::finite(scales.qs_star(qs)),
        shields: output::finite(scales.shields(tau_max)),
        shields_nominal: scales.shields_nominal,
        bed_height: output::finite(z1),
        transport_layer_thickness: output::finite(z99 - z1),
        steady: matches!(ending, Ending::Steady),
        ending: ending_name.into(),
        sim_time_s: m.time(),
        steps: m.steps(),
        rejected_steps: Some(m.rejected_steps()),
        wall_time_s: wall,
        mass_error: Some(m.mass_error()),
        residual: output::finite(m.residual()),
        cells: m.len(),
        error: ending.error(),
        particles: None,
        particle_steps_per_s: None,
        shields_turbulent: None,
    };
    // a column without moving grains (clear water) has no transport levels
    let layers = match (summary.bed_height, summary.transport_layer_thickness) {
        (Some(z1), Some(t)) => format!("bed surface {z1:.4} m, transport layer {t:.4} m"),
        _ => "no sediment transport".to_string(),
    };
    let text = format!(
        "{}: {} after {:.3} s simulated ({} steps, {} rejected) in {:.3} s wall time; qs* = {:.4} (qs = {:.4e} m^2/s), Shields {:.3}, {layers}, mass error {:.1e}",
        scene.meta.name,
        if summary.steady { "steady" } else { ending_name },
        summary.sim_time_s,
        summary.steps,
        m.rejected_steps(),
        wall,
        summary.qs_star.unwrap_or(f64::NAN),
        qs,
        summary.shields.unwrap_or(f64::NAN),
        m.mass_error()
    );
    RunReport { profiles: p, summary, text }
}
