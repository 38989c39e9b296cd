//! Profiles, summary and paragraph of a Lagrangian run, read from the solver through its
//! methods, with the same contract as the Eulerian solver.
//!
//! The profiles are time averages over the window from `solver.lagrangian.stats_start` to the end
//! of the run. A run that ends before its first sample (interrupted, unstable or out of
//! steps before `stats_start`, or without fluid: the samples are taken at the fluid
//! updates) has nothing to average: its profiles hold `z` only and its summary no
//! transport figure (absent, not zero). A scene whose window is empty by construction
//! (`end_time <= stats_start` with fluid) is refused at set-up.
//!
//! The standard error of qs comes from the blocking of its samples
//! ([`crate::lagrangian::stats::blocking::Blocking`]); the paragraph states its blocks, or why there is none. A
//! run without fluid reports its granular temperature history instead of transport
//! ([`Cooling`]), with Haff's law beside it for a homogeneous cooling scene.

use crate::lagrangian::run::config::FluidMode;
use crate::lagrangian::run::solver::Lagrangian;
use crate::lagrangian::stats::cooling::Cooling;
use crate::lagrangian::stats::truncation::Window;
use crate::measures::flux_levels::{flux_layer_thickness, flux_levels};
use crate::measures::rouse::rouse_number;
use crate::output::{finite, Profiles, Summary};
use crate::run::{Clock, Ending};
use crate::RunReport;

/// Profiles, summary and paragraph of `m` after a run that ended with `ending` with the
/// driver's clock at `clock`; the throughput is taken over the flow phase.
pub fn report(m: &Lagrangian<'_>, ending: &Ending, clock: &Clock) -> RunReport {
    let wall = clock.wall;
    let scene = m.scene();
    let n = m.cells();
    let dz = m.dz();
    let z: Vec<f64> = (0..n).map(|c| (c as f64 + 0.5) * dz).collect();
    let faces: Vec<f64> = (0..=n).map(|c| c as f64 * dz).collect();
    let mat = m.material();
    let scales = m.transport_scales();
    let samples = m.stats().samples;
    let mut p = Profiles::default();
    let z_c = z.clone();
    p.push("z", z);
    let mut transport = None;
    let mut rouse = None;
    if samples > 0 {
        let av = m.stats().averaged(m.cell_volume());
        let qs: f64 = av.q_s.iter().map(|q| q * dz).sum();
        let tau_max = av.tau_face.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let tau_t_max = av.tau_t.iter().fold(0.0f64, |a, t| a.max(*t));
        let (z1, z99) = flux_levels(&faces, &av.q_s, 0.01, 0.99);
        let layer = flux_layer_thickness(&faces, &av.q_s, scales.flux_velocity(mat.d));
        transport = Some((qs, tau_max, tau_t_max, z1, z99, layer));
        if m.has_fluctuation() {
            let d = &m.config().domain;
            let dzs = vec![dz; n];
            rouse = rouse_number(&z_c, &dzs, &av.phi, d.bed_height, d.water_depth);
        }
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
        if let Some(g) = m.granular_averages() {
            for (name, values) in g.columns() {
                p.push(name, values.to_vec());
            }
        }
    }
    let sample_period = m.dt() * m.fluid_every() as f64;
    let blocked = if samples > 0 { Some(m.stats().qs.estimate()) } else { None };
    let stderr = blocked.and_then(|b| b.ok()).and_then(|b| finite(b.stderr));
    let fluid = m.config().settings.numerics.fluid != FluidMode::Off;
    let cooling = &m.stats().cooling;
    let dry = (!fluid && cooling.samples > 0).then_some(cooling);
    let haff = m.haff_constant().filter(|_| dry.is_some());
    let mobile = m.mobile();
    let flow_wall = clock.flow;
    let throughput = (flow_wall > 0.0).then(|| mobile as f64 * m.steps() as f64 / flow_wall);
    let window = if fluid { m.truncation().window() } else { None };
    let summary = Summary {
        scene: scene.meta.name.clone(),
        solver: "lagrangian".into(),
        qs: transport.map(|t| t.0),
        qs_star: transport.and_then(|t| finite(scales.qs_star(t.0))),
        qs_stderr: stderr,
        qs_star_stderr: stderr.and_then(|e| finite(scales.qs_star(e))),
        shields: transport.and_then(|t| finite(scales.shields(t.1))),
        shields_nominal: scales.shields_nominal,
        bed_height: transport.and_then(|t| finite(t.3)),
        transport_layer_thickness: transport.and_then(|t| finite(t.4 - t.3)),
        flux_layer_thickness: transport.and_then(|t| finite(t.5)),
        steady: matches!(ending, Ending::Steady),
        ending: ending.name().into(),
        sim_time_s: m.time(),
        steps: m.steps() as usize,
        total_steps: Some((m.settle_steps() + m.steps()) as usize),
        samples: Some(samples),
        rejected_steps: None,
        wall_time_s: wall,
        cpu_time_s: None,
        mass_error: None,
        residual: m.steady().change(),
        cells: n,
        error: ending.error(),
        particles: Some(mobile),
        particle_steps_per_s: throughput,
        shields_turbulent: transport.filter(|_| scales.stress > 0.0).and_then(|t| finite(scales.shields(t.2))),
        granular_temperature: dry.and_then(|_| finite(m.particles().temperature())),
        haff_tau_s: haff.and_then(|h| cooling.haff_tau(h)).and_then(finite),
        haff_tau_fit_s: haff.and(cooling.fitted_tau()).and_then(finite),
        haff_granular_temperature: haff.and_then(|h| cooling.haff_at(h, m.time())).and_then(finite),
        haff_max_deviation: haff.and_then(|_| finite(cooling.max_deviation)),
        rouse_number: rouse,
        net_transport: None,
        net_transport_stderr: None,
        window_start_s: window.map(|w| w.start),
        qs_window: window.and_then(|w| finite(w.mean)),
        qs_window_stderr: window.and_then(|w| w.stderr).and_then(finite),
        qs_window_geweke_z: window.and_then(|w| w.geweke_z).and_then(finite),
        qs_window_inefficiency_s: window.filter(|w| w.stderr.is_some()).and_then(|w| w.inefficiency_s).and_then(finite),
        neighbour_builds: Some(m.dem().list().builds),
        timing: None,
    };
    let measured = match (summary.qs_star, summary.shields) {
        (None, _) | (_, None) if samples > 0 => format!(
            "qs = {:.4e} m^2/s{} (qs* and Shields undefined: no gravity or no density contrast to scale them)",
            summary.qs.unwrap_or(0.0),
            match (blocked, stderr) {
                (Some(Ok(_)), Some(e)) => format!(" +- {e:.4e} (standard error, blocking)"),
                (Some(Err(why)), _) => format!(" (no standard error: {why})"),
                _ => String::new(),
            }
        ),
        (Some(q), Some(sh)) => {
            let layers = match (summary.bed_height, summary.transport_layer_thickness) {
                (Some(b), Some(t)) => format!("bed surface {b:.4} m, transport layer {t:.4} m"),
                _ => "no sediment transport".into(),
            };
            let error = match (blocked, summary.qs_star_stderr) {
                (Some(Ok(b)), Some(e)) => {
                    let span = b.block_samples as f64 * sample_period;
                    let correlation = b
                        .inefficiency()
                        .map(|s| {
                            // statistical inefficiency = 2 x the integrated correlation time
                            let tau = 0.5 * s * sample_period;
                            format!(
                                "; integrated correlation time of qs(t) {tau:.3} s, blocks {:.1} times longer",
                                span / tau
                            )
                        })
                        .unwrap_or_default();
                    format!(
                        " +- {e:.4} (standard error of the time average: Flyvbjerg-Petersen blocking of the {samples} qs samples, {} blocks of {} samples = {span:.3} s, the shortest blocks whose means pass Jonsson's lag-1 test{correlation})",
                        b.blocks, b.block_samples
                    )
                }
                (Some(Err(why)), _) => format!(" (no standard error: {why})"),
                _ => String::new(),
            };
            format!(
                "qs* = {q:.4}{error} (qs = {:.4e} m^2/s), Shields {sh:.3} (turbulent theta* {}), {layers}",
                summary.qs.unwrap_or(0.0),
                summary.shields_turbulent.map_or_else(|| "undefined".into(), |t| format!("{t:.3}")),
            )
        }
        _ => format!(
            "no averaging sample (the window opens at solver.lagrangian.stats_start = {} s{}): no transport figures",
            m.config().settings.numerics.stats_start,
            if m.config().settings.numerics.fluid == FluidMode::Off {
                ", and runs without fluid take none"
            } else {
                ""
            }
        ),
    };
    let steady = steady_sentence(m, fluid);
    let window = window_sentence(m, fluid, window);
    let temperature = dry
        .map(|c| cooling_sentence(c, haff, m.time(), summary.granular_temperature.unwrap_or(0.0)))
        .unwrap_or_default();
    let text = format!(
        "{}: {} after {} s of flow ({} DEM steps of {:.3e} s after {} of deposition, {} in all, {} neighbour-list builds, {} mobile particles, {samples} averaging samples) in {:.1} s wall time ({:.2e} particle-steps/s); {measured}; {window}; {steady}{temperature}",
        scene.label(),
        ending.name(),
        saltus_core::param::decimal(summary.sim_time_s),
        summary.steps,
        m.dt(),
        m.settle_steps(),
        m.settle_steps() + m.steps(),
        m.dem().list().builds,
        mobile,
        wall,
        throughput.unwrap_or(0.0),
    );
    RunReport { profiles: p, summary, text }
}

/// The averaging window MSER-5 finds in the run's transport rate, the rate over it and
/// the stopping rule on a requested error.
fn window_sentence(m: &Lagrangian<'_>, fluid: bool, window: Option<Window>) -> String {
    if !fluid {
        return "no averaging window found (a run without fluid does not measure its transport rate)".into();
    }
    let target = m.config().settings.numerics.target_error;
    let rule = target.map_or_else(String::new, |t| format!("; target relative error {t}"));
    match window {
        None => format!("averaging window (MSER-5 on the transport rate): none yet, the rate has not levelled{rule}"),
        Some(w) => {
            let floor = m.truncation().prior().map_or_else(String::new, |p| {
                format!(", the developed state's statistical inefficiency {p:.3} s as its floor")
            });
            let error = match (w.stderr, w.relative_error()) {
                (Some(e), Some(r)) => format!(" +- {e:.4e} (relative {r:.2e}{floor})"),
                _ => format!(" (no standard error: too few blocks{floor})"),
            };
            let level = w.geweke_z.map_or_else(
                || "level: not tested (too few blocks)".to_string(),
                |z| format!("Geweke z {z:.2} between its first 10 % and last 50 %"),
            );
            format!(
                "averaging window (MSER-5 on the transport rate) from t = {} s: qs = {:.4e}{error} m^2/s over {} fluid updates, {level}{rule}",
                saltus_core::param::decimal(w.start),
                w.mean,
                w.samples
            )
        }
    }
}

/// The steady test as the run met it: criterion, windows, last change against the
/// tolerance.
fn steady_sentence(m: &Lagrangian<'_>, fluid: bool) -> String {
    if !fluid {
        return "no steady test (it is on the transport rate, which a run without fluid does not measure)".into();
    }
    let st = m.steady();
    let (window, tolerance, needed) = st.criterion();
    let rule = format!(
        "steady test: relative change of the mean transport rate between consecutive {window} s windows (from t = 0) within {tolerance} for {needed} consecutive windows"
    );
    match st.change() {
        None => format!("{rule}: fewer than two complete windows, no change measured yet (not steady)"),
        Some(c) => format!(
            "{rule}: last change {c:.4} against {tolerance}, {} of {needed} consecutive windows within ({})",
            st.streak().min(needed),
            if st.is_steady() { "steady" } else { "not steady" }
        ),
    }
}

/// The temperature history of a run without fluid, which ends at `time` with the
/// temperature `last`, and, for a cooling scene, Haff's law.
fn cooling_sentence(c: &Cooling, haff: Option<f64>, time: f64, last: f64) -> String {
    let history = format!(
        "; granular temperature {:.4e} -> {last:.4e} m^2/s^2 over {time:.3} s (column theta_g of timeseries.csv; {} samples, one per fluid period, for Haff's law)",
        c.initial, c.samples
    );
    let comparison = match haff.and_then(|h| Some((c.haff_tau(h)?, c.haff_at(h, time)?))) {
        Some((tau, predicted)) => format!(
            "; Haff's law T0 / (1 + t/tau)^2: tau = {tau:.4} s from the kinetic theory, {} fitted; T at the end {:+.2} % from Haff's {predicted:.4e}, largest deviation {:.2} % over the samples",
            c.fitted_tau().map_or_else(|| "none".into(), |t| format!("{t:.4} s")),
            100.0 * (last / predicted - 1.0),
            100.0 * c.max_deviation
        ),
        None => "; no Haff comparison: the scene is not a homogeneous cooling one (inelastic frictionless gas, no body force, triply periodic box)".into(),
    };
    history + &comparison
}
