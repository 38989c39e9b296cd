//! Profiles, summary and paragraph of a Lagrangian run, read from the solver through its
//! methods, with the same contract as the Eulerian solver.
//!
//! The profiles are time averages over the window from `solver.lagrangian.stats_start` to the end
//! of the run. A run that ends before its first sample (interrupted, unstable or out of
//! steps before `stats_start`, or without fluid: the samples are taken at the fluid
//! updates) has nothing to average: its profiles hold `z` only and its summary no
//! transport figure (absent, not zero). A scene whose window is empty by construction
//! (`end_time <= stats_start` with fluid) is refused at set-up.

use super::solver::Lagrangian;
use crate::output::{self, finite, Profiles, Summary};
use crate::run::Ending;
use crate::RunReport;

/// Profiles, summary and paragraph of `m` after a run that ended with `ending` after
/// `wall` seconds of wall-clock time; the throughput is taken over the flow phase.
pub fn report(m: &Lagrangian<'_>, ending: &Ending, wall: f64) -> RunReport {
    let scene = m.scene();
    let n = m.cells();
    let dz = m.dz();
    let z: Vec<f64> = (0..n).map(|c| (c as f64 + 0.5) * dz).collect();
    let faces: Vec<f64> = (0..=n).map(|c| c as f64 * dz).collect();
    let mat = m.material();
    let scales = output::TransportScales::new(scene, mat.rho_p, mat.d, m.config().domain.water_depth);
    let samples = m.stats().samples;
    let mut p = Profiles::default();
    p.push("z", z);
    let mut transport = None;
    if samples > 0 {
        let av = m.stats().averaged(m.cell_volume());
        let qs: f64 = av.q_s.iter().map(|q| q * dz).sum();
        let tau_max = av.tau_face.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let tau_t_max = av.tau_t.iter().fold(0.0f64, |a, t| a.max(*t));
        let (z1, z99) = output::flux_levels(&faces, &av.q_s, 0.01, 0.99);
        transport = Some((qs, tau_max, tau_t_max, z1, z99));
        p.push("phi", av.phi);
        p.push("u_f", av.u_f);
        p.push("u_p", av.v[0].clone());
        p.push("w_p", av.v[2].clone());
        p.push("q_s", av.q_s);
        let [vxx, vyy, vzz, vxz] = av.vv;
        p.push("vxx", vxx);
        p.push("vyy", vyy);
        p.push("vzz", vzz);
        p.push("vxz", vxz);
        p.push("theta_g", av.temperature);
        p.push("tau_t", av.tau_t);
        p.push("tau_f", av.tau_face.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect());
        p.push("nu_t", av.nu_t);
        p.push("beta", av.beta);
    }
    let mobile = m.mobile();
    let flow_wall = m.flow_wall();
    let throughput = (flow_wall > 0.0).then(|| mobile as f64 * m.steps() as f64 / flow_wall);
    let summary = Summary {
        scene: scene.meta.name.clone(),
        solver: "lagrangian".into(),
        qs: transport.map(|t| t.0),
        qs_star: transport.and_then(|t| finite(scales.qs_star(t.0))),
        shields: transport.and_then(|t| finite(scales.shields(t.1))),
        shields_nominal: scales.shields_nominal,
        bed_height: transport.and_then(|t| finite(t.3)),
        transport_layer_thickness: transport.and_then(|t| finite(t.4 - t.3)),
        steady: matches!(ending, Ending::Steady),
        ending: ending.name().into(),
        sim_time_s: m.time(),
        steps: m.steps() as usize,
        rejected_steps: None,
        wall_time_s: wall,
        mass_error: None,
        residual: m.steady().change(),
        cells: n,
        error: ending.error(),
        particles: Some(mobile),
        particle_steps_per_s: throughput,
        shields_turbulent: transport.filter(|_| scales.stress > 0.0).and_then(|t| finite(scales.shields(t.2))),
    };
    let measured = match (summary.qs_star, summary.shields) {
        (Some(q), Some(sh)) => {
            let layers = match (summary.bed_height, summary.transport_layer_thickness) {
                (Some(b), Some(t)) => format!("bed surface {b:.4} m, transport layer {t:.4} m"),
                _ => "no sediment transport".into(),
            };
            format!(
                "qs* = {q:.4} (qs = {:.4e} m^2/s), Shields {sh:.3} (turbulent theta* {:.3}), {layers}",
                summary.qs.unwrap_or(0.0),
                summary.shields_turbulent.unwrap_or(f64::NAN),
            )
        }
        _ => format!(
            "no averaging sample (the window opens at solver.lagrangian.stats_start = {} s{}): no transport figures",
            m.config().settings.numerics.stats_start,
            if m.config().settings.numerics.fluid == super::config::FluidMode::Off {
                ", and runs without fluid take none"
            } else {
                ""
            }
        ),
    };
    let mut text = format!(
        "{}: {} after {:.3} s of flow ({} DEM steps of {:.3e} s after {} of deposition, {} neighbour-list builds, {} mobile particles, {samples} samples) in {:.1} s wall time ({:.2e} particle-steps/s); {measured}",
        scene.meta.name,
        ending.name(),
        summary.sim_time_s,
        summary.steps,
        m.dt(),
        m.settle_steps(),
        m.dem().list().builds,
        mobile,
        wall,
        throughput.unwrap_or(0.0),
    );
    if let Some(e) = m.vtk_error() {
        text.push_str("; ");
        text.push_str(e);
    }
    RunReport { profiles: p, summary, text }
}
