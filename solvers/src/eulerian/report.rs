//! Profiles, summary and paragraph of an Eulerian run, read from the state and the
//! coefficients the stepper keeps current: nothing here advances or evaluates anything.
//!
//! Every number written is finite. `phi` is written clamped into [0, phi_max] (the phi
//! step accepts round-off negatives down to -1e-9, which are not volume fractions). The
//! control number (`inertial_number` of kinetic theory and mu(I), `control_number` of
//! mu(K)) is undefined where the grains carry no pressure (I = d gamma_dot / sqrt(p /
//! rho_p) is infinite at p = 0, a sheared cell without grains in contact or collision);
//! such cells are NaN in the profiles and an empty cell in `profiles.csv`.

use super::rheology::Rheology;
use super::stress::local_state;
use super::Eulerian;
use crate::measures::flux_levels::{flux_layer_thickness, flux_levels, flux_levels_by};
use crate::measures::rouse::rouse_number;
use crate::output::{self, Profiles, Summary};
use crate::run::{Ending, Sample};
use crate::RunReport;

/// Derived cell profiles, see [`Eulerian::derived`].
#[derive(Clone, Debug, Default)]
pub struct Derived {
    /// particle shear stress (Pa)
    pub tau_p: Vec<f64>,
    /// fluid shear stress, viscous + turbulent (Pa)
    pub tau_f: Vec<f64>,
    /// particle pressure (Pa)
    pub p_p: Vec<f64>,
    /// particle wall-normal velocity (m/s)
    pub w_p: Vec<f64>,
    /// inertial number I (kinetic and mu(I)) or K (mu(K)); NaN where the particle pressure
    /// vanishes and the number is undefined (see the module documentation)
    pub control: Vec<f64>,
}

impl Eulerian<'_> {
    /// Profiles of derived fields at the current state, cell-centred: particle shear stress,
    /// fluid shear stress (viscous + turbulent), particle pressure, particle wall-normal
    /// velocity, the control number of the granular closure.
    pub fn derived(&self) -> Derived {
        let n = self.len();
        let (s, co) = (&self.state, &self.work.co);
        let nu_t = s.eddy.values();
        let mut out = Derived::default();
        for i in 0..nu_t.len().min(n) {
            out.tau_p.push(0.5 * (co.tau_p[i] + co.tau_p[i + 1]));
            out.tau_f.push(self.fluid_shear_stress(i));
            let p = co.pres[i].p + co.overburden[i];
            out.p_p.push(p);
            let f = 0.5 * (s.flux[i] + s.flux[i + 1]);
            out.w_p.push(if s.phi[i] > 1e-6 { f / s.phi[i] } else { 0.0 });
            let x = match self.params.m.rheology {
                Rheology::Local { model, .. } => model.control_number(&local_state(&self.params, co.gamma_p[i], p)),
                Rheology::Kinetic { .. } => local_state(&self.params, co.gamma_p[i], co.pres[i].p).inertial_number(),
            };
            out.control.push(if x.is_finite() { x } else { f64::NAN });
        }
        out
    }

    /// The granular fields under the names of the DEM's averaged fields (see
    /// `docs/diagnostics.md`), evaluated with the run's closure at the written cell state
    /// so that `saltus diagnose` of this run finds the closure again: `gamma_dot` (the
    /// cell shear rate of u_p), `inertial_number` (local rheologies; kinetic runs write it
    /// already), `viscous_number`, `mu_eff` (the closure's stress over p_p at the cell
    /// state: mu(X) of a local rheology, (rho_p d F2 sqrt(T) gamma_dot + mu_s p_el) / p_p
    /// of kinetic theory, without the regularisation of the momentum step), `beta` (phi (1 -
    /// phi) K, eq 2.10), and for kinetic theory `heat_flux` (-kappa dT/dz, eqs 2.18, 2.21),
    /// `dissipation` (Gamma = rho_p / d F4' T^1.5, eq 2.22) and `drag_dissipation`
    /// (J_int = -c_J beta T, eqs 2.25 / 3.13). Undefined values (p_p = 0) are NaN.
    fn push_granular_fields(&self, p: &mut Profiles, p_p: &[f64]) {
        let n = self.len();
        let (c, co) = (self.params.c, &self.work.co);
        let gamma = &co.gamma_p[..n];
        let state = |i: usize| local_state(&self.params, gamma[i], p_p[i]);
        let defined = |x: f64| if x.is_finite() { x } else { f64::NAN };
        let per_cell = |f: &dyn Fn(usize) -> f64| (0..n).map(f).map(defined).collect::<Vec<_>>();
        p.push("gamma_dot", gamma.to_vec());
        let mu_eff = match self.params.m.rheology {
            Rheology::Local { model, .. } => {
                p.push("inertial_number", per_cell(&|i| state(i).inertial_number()));
                per_cell(&|i| if p_p[i] > 0.0 { model.friction(model.control_number(&state(i))) } else { f64::NAN })
            }
            Rheology::Kinetic { model: kt, .. } => {
                let mu_s = kt.static_friction();
                per_cell(&|i| {
                    let st = self.state.temp[i].max(0.0).sqrt();
                    let g = gamma[i];
                    let coulomb = if g == 0.0 { 0.0 } else { mu_s * co.pres[i].p_el * g.signum() };
                    (kt.shear_viscosity(&co.coef[i], c.rho_p, c.d, st) * g + coulomb) / p_p[i]
                })
            }
        };
        p.push("viscous_number", per_cell(&|i| state(i).viscous_number()));
        p.push("mu_eff", mu_eff);
        p.push("beta", co.beta[..n].to_vec());
        let Rheology::Kinetic { model: kt, .. } = self.params.m.rheology else { return };
        let temp = &self.state.temp[..n];
        let dtdz = output::profile_gradient(self.z(), temp);
        p.push("heat_flux", per_cell(&|i| -co.kappa[i] * dtdz[i]));
        p.push("dissipation", per_cell(&|i| kt.dissipation(&co.coef[i], c.rho_p, c.d, temp[i].max(0.0))));
        let cd_inf = self.params.m.drag.cd_inf();
        p.push(
            "drag_dissipation",
            per_cell(&|i| {
                let c_j = kt.drag_dissipation_factor(cd_inf, cd_inf / co.cd_ratio[i].max(1e-300));
                -c_j * co.beta[i] * temp[i].max(0.0)
            }),
        );
    }

    /// Fluid shear stress, viscous + turbulent, of cell `i` (Pa).
    fn fluid_shear_stress(&self, i: usize) -> f64 {
        let (s, co, c) = (&self.state, &self.work.co, self.params.c);
        let eps = 1.0 - s.phi[i].max(0.0);
        c.rho_f * eps * (c.nu_f * co.visc_ratio[i] + s.eddy.values()[i]) * co.gamma_f[i]
    }

    /// The state as a row of the time series: qs, the largest fluid shear stress and the
    /// 1 % level of the transport as the report computes them, and the steady residual.
    pub(super) fn sample_row(&self) -> Sample {
        let scales = self.params.scales;
        let (phi, up, dz, faces) = (self.phi(), self.u_p(), self.dz(), self.faces());
        let q = |i: usize| phi[i].max(0.0) * up[i];
        let qs: f64 = (0..self.len()).map(|i| q(i) * dz[i]).sum();
        let tau = (0..self.len()).fold(0.0f64, |a, i| a.max(self.fluid_shear_stress(i).abs()));
        let (z1, _) = flux_levels_by(self.len(), |i| faces[i], q, 0.01, 0.99);
        Sample {
            time: self.time(),
            qs: output::finite(qs),
            qs_star: output::finite(scales.qs_star(qs)),
            shields: output::finite(scales.shields(tau)),
            bed_surface: output::finite(z1),
            residual: output::finite(self.residual()),
            steps: self.steps() as u64,
            theta_g: None,
        }
    }

    /// Profiles, summary and paragraph of the run as it is now, ended by `ending` after
    /// `wall` seconds.
    pub(super) fn run_report(&self, ending: &Ending, wall: f64) -> RunReport {
        let scene = self.params.scene;
        let derived = self.derived();
        let phi_max = self.params.m.rheology.phi_max();
        let phi: Vec<f64> = self.phi().iter().map(|p| p.clamp(0.0, phi_max)).collect();
        let mut p = Profiles::default();
        p.push("z", self.z().to_vec());
        p.push("phi", phi.clone());
        p.push("u_f", self.u_f().to_vec());
        p.push("u_p", self.u_p().to_vec());
        if self.is_kinetic() {
            p.push("theta_g", self.temperature().to_vec());
        }
        p.push("w_p", derived.w_p);
        p.push("p_p", derived.p_p.clone());
        p.push("tau_p", derived.tau_p);
        p.push("tau_f", derived.tau_f.clone());
        p.push("nu_t", self.eddy_viscosity().to_vec());
        if let Some((k, omega)) = self.k_omega() {
            p.push("k", k.to_vec());
            p.push("omega", omega.to_vec());
        }
        let q: Vec<f64> = phi.iter().zip(self.u_p()).map(|(a, b)| a * b).collect();
        p.push("q_s", q.clone());
        p.push(if self.is_kinetic() { "inertial_number" } else { "control_number" }, derived.control);
        self.push_granular_fields(&mut p, &derived.p_p);

        let qs: f64 = q.iter().zip(self.dz()).map(|(q, h)| q * h).sum();
        let tau_max = derived.tau_f.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let scales = self.params.scales;
        let (z1, z99) = flux_levels(self.faces(), &q, 0.01, 0.99);
        let summary = Summary {
            scene: scene.meta.name.clone(),
            solver: "eulerian".into(),
            qs: output::finite(qs),
            qs_star: output::finite(scales.qs_star(qs)),
            shields: output::finite(scales.shields(tau_max)),
            shields_nominal: scales.shields_nominal,
            bed_height: output::finite(z1),
            transport_layer_thickness: output::finite(z99 - z1),
            flux_layer_thickness: output::finite(flux_layer_thickness(
                self.faces(),
                &q,
                scales.flux_velocity(scene.particles.diameter),
            )),
            steady: matches!(ending, Ending::Steady),
            ending: ending.name().into(),
            sim_time_s: self.time(),
            steps: self.steps(),
            rejected_steps: Some(self.rejected_steps()),
            wall_time_s: wall,
            cpu_time_s: None,
            mass_error: Some(self.mass_error()),
            residual: output::finite(self.residual()),
            cells: self.len(),
            error: ending.error(),
            particles: None,
            particle_steps_per_s: None,
            shields_turbulent: None,
            rouse_number: self.params.m.fluctuation.and_then(|_| {
                let d = &self.params.scene.domain;
                rouse_number(self.z(), self.dz(), &phi, d.bed_height, d.water_depth)
            }),
            ..Summary::default()
        };
        // a column without moving grains (clear water) has no transport levels
        let layers = match (summary.bed_height, summary.transport_layer_thickness) {
            (Some(z1), Some(t)) => format!("bed surface {z1:.4} m, transport layer {t:.4} m"),
            _ => "no sediment transport".to_string(),
        };
        let figure = |x: Option<f64>, f: fn(f64) -> String| x.map_or_else(|| "undefined".to_string(), f);
        let text = format!(
            "{}: {} after {} s simulated ({} steps, {} rejected) in {:.3} s wall time; qs* = {} (qs = {:.4e} m^2/s), Shields {}, {layers}, mass error {:.1e}",
            scene.label(),
            ending.name(),
            saltus_core::param::decimal(summary.sim_time_s),
            summary.steps,
            self.rejected_steps(),
            wall,
            figure(summary.qs_star, |v| format!("{v:.4}")),
            qs,
            figure(summary.shields, |v| format!("{v:.3}")),
            self.mass_error()
        );
        let text = match summary.rouse_number {
            Some(ro) => format!("{text}, Rouse number {ro:.3}"),
            None => text,
        };
        RunReport { profiles: p, summary, text }
    }
}
