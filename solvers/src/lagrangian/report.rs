//! `saltus run` of a Lagrangian scene: the run in its thread pool, then the profiles and
//! the summary of the same contract as the Eulerian solver.

use std::path::Path;
use std::time::Instant;

use saltus_core::scene::Scene;
use saltus_core::Error;

use super::config::Config;
use super::solver::{Ending, Lagrangian};
use crate::eulerian::Progress;
use crate::output::{self, Profiles, Summary};
use crate::RunReport;

/// Run `f` in `pool` (all cores when `None`).
pub fn within<R: Send>(pool: Option<&rayon::ThreadPool>, f: impl FnOnce() -> R + Send) -> R {
    match pool {
        Some(p) => p.install(f),
        None => f(),
    }
}

/// A pool of `threads` threads, or `None` for rayon's default (all cores).
pub fn pool(threads: usize, file: &Path) -> Result<Option<rayon::ThreadPool>, Error> {
    if threads == 0 {
        return Ok(None);
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map(Some)
        .map_err(|e| Error::Invalid(format!("{}: solver.threads = {threads}: {e}", file.display())))
}

/// Run a Lagrangian scene and write its outputs into `out` (VTK snapshots into
/// `out/vtk` when asked). A run that breaks down writes what it has and returns the error.
pub fn run(scene: &Scene, out: &Path, observer: &mut dyn FnMut(&Progress) -> bool) -> Result<RunReport, Error> {
    let cfg = Config::from_scene(scene)?;
    let pool = pool(cfg.settings.threads, &scene.path)?;
    let mut model = Lagrangian::new(scene, cfg)?;
    model.set_vtk_dir(&out.join("vtk"));
    let start = Instant::now();
    let mut flow_start = start;
    let ending = match within(pool.as_ref(), || model.start()) {
        Err(b) => Ending::Unstable(b),
        Ok(()) => {
            flow_start = Instant::now();
            loop {
                if let Some(e) = within(pool.as_ref(), || model.advance()) {
                    break e;
                }
                if !observer(&model.progress()) {
                    break Ending::EndTime;
                }
            }
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let flow_wall = flow_start.elapsed().as_secs_f64();
    let report = report(scene, &model, &ending, wall, flow_wall);
    output::write_run(out, scene, &report.profiles, &report.summary)?;
    if let Ending::Unstable(b) = ending {
        return Err(Error::Invalid(format!(
            "{}: run stopped, unstable at {b}; the state at t = {:.6} s is written to {}",
            scene.path.display(),
            model.time(),
            out.display()
        )));
    }
    Ok(report)
}

/// Profiles, summary and paragraph of a Lagrangian run; `flow_wall` is the wall time of
/// the flow phase (after the deposition), used for the throughput.
pub fn report(scene: &Scene, m: &Lagrangian<'_>, ending: &Ending, wall: f64, flow_wall: f64) -> RunReport {
    let n = m.field.u.len();
    let dz = m.dz();
    let av = m.stats().averaged(m.cell_volume());
    let z: Vec<f64> = (0..n).map(|c| (c as f64 + 0.5) * dz).collect();
    let faces: Vec<f64> = (0..=n).map(|c| c as f64 * dz).collect();
    let mut p = Profiles::default();
    p.push("z", z);
    p.push("phi", av.phi.clone());
    p.push("u_f", av.u_f.clone());
    p.push("u_p", av.v[0].clone());
    p.push("w_p", av.v[2].clone());
    p.push("q_s", av.q_s.clone());
    p.push("vxx", av.vv[0].clone());
    p.push("vyy", av.vv[1].clone());
    p.push("vzz", av.vv[2].clone());
    p.push("vxz", av.vv[3].clone());
    p.push("theta_g", av.temperature.clone());
    p.push("tau_t", av.tau_t.clone());
    p.push("tau_f", av.tau_face.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect());
    p.push("nu_t", av.nu_t.clone());
    p.push("beta", av.beta.clone());

    let mat = m.material();
    let d = mat.d;
    let qs: f64 = av.q_s.iter().map(|q| q * dz).sum();
    let scales = output::TransportScales::new(scene, mat.rho_p, d, m.config().domain.water_depth);
    let tau_max = av.tau_face.iter().fold(0.0f64, |a, t| a.max(t.abs()));
    let tau_t_max = av.tau_t.iter().fold(0.0f64, |a, t| a.max(*t));
    let (z1, z99) = output::flux_levels(&faces, &av.q_s, 0.01, 0.99);
    let (ending_name, error) = match ending {
        Ending::Steady => ("steady", None),
        Ending::EndTime => ("end_time", None),
        Ending::MaxSteps => ("max_steps", None),
        Ending::Unstable(b) => ("unstable", Some(b.to_string())),
    };
    let mobile = m.mobile();
    let throughput = (flow_wall > 0.0).then(|| mobile as f64 * m.steps() as f64 / flow_wall);
    let summary = Summary {
        scene: scene.meta.name.clone(),
        solver: "lagrangian".into(),
        qs,
        qs_star: scales.qs_star(qs),
        shields: scales.shields(tau_max),
        shields_nominal: scales.shields_nominal,
        bed_height: z1,
        transport_layer_thickness: z99 - z1,
        steady: m.steady().is_steady(),
        ending: ending_name.into(),
        sim_time_s: m.time(),
        steps: m.steps() as usize,
        rejected_steps: None,
        wall_time_s: wall,
        mass_error: None,
        residual: m.steady().change,
        cells: n,
        error,
        particles: Some(mobile),
        particle_steps_per_s: throughput,
        shields_turbulent: (scales.stress > 0.0).then(|| scales.shields(tau_t_max)),
    };
    let text = format!(
        "{}: {} after {:.3} s of flow ({} DEM steps of {:.3e} s, {} neighbour-list builds, {} mobile particles, {} samples) in {:.1} s wall time ({:.2e} particle-steps/s); qs* = {:.4} (qs = {:.4e} m^2/s), Shields {:.3} (turbulent theta* {:.3}), bed surface {:.4} m, transport layer {:.4} m",
        scene.meta.name,
        if summary.steady { "steady" } else { ending_name },
        summary.sim_time_s,
        summary.steps,
        m.dt(),
        m.dem.list.builds,
        mobile,
        m.stats().samples,
        wall,
        throughput.unwrap_or(0.0),
        summary.qs_star,
        qs,
        summary.shields,
        summary.shields_turbulent.unwrap_or(f64::NAN),
        z1,
        summary.transport_layer_thickness,
    );
    RunReport { profiles: p, summary, text }
}
