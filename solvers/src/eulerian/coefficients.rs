//! Everything the Eulerian step recomputes from the state: shear rates, the drag of the
//! drag kernel, the fluid diffusivities and conductances, the eddy viscosity, the drift
//! diffusivity and (in [`super::stress`]) the particle pressure and stress, with the
//! scratch space of the solves. One batch call per closure family per evaluation.

use saltus_core::{ColumnView, TurbulencePoint};

use super::rheology::Rheology;
use super::solver::{breakdown, Params, Workspace};
use super::state::State;
use super::stress::{evaluate_stress, local_pressures};
use super::Eulerian;
use crate::inputs;
use crate::run::Breakdown;

/// Relative step of the batch difference of the drag kernel in Re.
const DRE: f64 = 1e-6;

impl Eulerian<'_> {
    /// Every coefficient of the step from the current state; the eddy viscosity (state,
    /// lagged) takes its relaxed update here, once per evaluation.
    pub(super) fn evaluate(&mut self) -> Result<(), Breakdown> {
        evaluate(&self.params, &mut self.state, &mut self.work, true)
    }
}

/// Shear rates at cells and faces of the current u_f and u_p.
pub(super) fn shear_rates(params: &Params, state: &State, work: &mut Workspace) {
    let top_f = params.fluid_top(&state.uf);
    let top_p = params.op.stress_free_shear_top(&state.up);
    params.op.shear_rate(&state.uf, top_f, &mut work.co.gamma_f);
    params.op.shear_rate(&state.up, top_p, &mut work.co.gamma_p);
    params.op.face_gradient(&state.up, &mut work.co.face_gamma);
}

/// Every coefficient of the step from `state`, with the eddy viscosity updated or
/// (`update_eddy` false) kept as it is: the evaluation at the extrapolated state of a
/// BDF2 step keeps the relaxed nu_t of the last accepted state, so that nu_t is relaxed
/// once per step whatever the stepping (an unrelaxed mixing length destabilises the
/// oscillatory sheet flow).
pub(super) fn evaluate(
    params: &Params,
    state: &mut State,
    work: &mut Workspace,
    update_eddy: bool,
) -> Result<(), Breakdown> {
    shear_rates(params, state, work);
    evaluate_drag(params, state, work);
    let c = params.c;
    params.m.viscosity.ratio_batch(&state.phi, &mut work.co.visc_ratio);
    let kw_fields = state.kw.as_ref().map(|kw| kw.col.fields());
    let transported: &[&[f64]] = kw_fields.as_ref().map_or(&[], |f| f.as_slice());
    let col = ColumnView {
        z: params.op.grid().centres(),
        dz: params.op.grid().dz(),
        phi: &state.phi,
        dudz: &work.co.gamma_f,
        diameter: c.d,
        nu_f: c.nu_f,
        transported,
    };
    let first = state.steps == 0;
    if update_eddy {
        if let Err(i) = state.eddy.evaluate(params.m.turbulence, &col) {
            return Err(breakdown(params, state, i, "nu_t", f64::NAN, "eddy viscosity not finite or negative".into()));
        }
        state.eddy.relax(first);
    }
    let nu_t = state.eddy.values();
    for (i, &nt) in nu_t.iter().enumerate() {
        let eps = 1.0 - state.phi[i].max(0.0);
        work.co.fluid_k[i] = eps * (c.nu_f * work.co.visc_ratio[i] + nt);
    }
    params.op.conductances(c.rho_f, &work.co.fluid_k, &mut work.co.fluid_cond);
    evaluate_drift(params, state, work);
    evaluate_stress(params, state, work);
    Ok(())
}

/// K of eq 2.10 from the drag kernel with the full slip magnitude (streamwise and
/// wall-normal), with the tangent of the streamwise drag from one batch difference.
fn evaluate_drag(params: &Params, state: &State, work: &mut Workspace) {
    let n = state.len();
    let c = params.c;
    let sc = &mut work.sc;
    for i in 0..n {
        let phi = state.phi[i].clamp(0.0, 1.0 - 1e-12);
        // the slip of eq 4.3, u_f - u_p + u_d: the particle flux less its drift part
        let f = 0.5 * (state.flux[i] + state.flux[i + 1]) - 0.5 * (state.drift_flux[i] + state.drift_flux[i + 1]);
        let wp = if phi > params.slip_phi { f / phi } else { 0.0 };
        let slip = crate::inputs::mean_slip(state.uf[i], state.up[i], wp, phi);
        sc.phi_c[i] = phi;
        sc.work[i] = slip;
        sc.re[i] = slip * c.d / c.nu_f;
        sc.re2[i] = sc.re[i] * (1.0 + DRE);
    }
    params.kernel.evaluate(&sc.phi_c, &sc.re, &mut sc.drag);
    params.kernel.evaluate_at_reynolds(&sc.drag, &sc.phi_c, &sc.re2, &mut sc.drag2);
    let stokes = 0.75 * c.rho_f * c.nu_f / (c.d * c.d);
    let cd_inf = params.m.drag.cd_inf();
    let co = &mut work.co;
    for i in 0..n {
        let phi = sc.phi_c[i];
        let eps = 1.0 - phi;
        let re = sc.re[i];
        let (re_h, cdre, fh) = (sc.drag.re_star[i], sc.drag.cd_re[i], sc.drag.factor[i]);
        // C_D(Re*) |u_r| = cd_re(Re*) nu / d / c(phi): finite as Re -> 0
        let conv = 1.0 / params.kernel.reynolds_ratio(phi);
        // C = phi eps K / phi (kg m^-3 s^-1): beta = phi C, K = C / eps
        let cc = stokes * fh * cdre * conv;
        // d ln C / d ln Re for the Newton linearisation of the streamwise drag: a Picard
        // lag of a quadratic drag (slip <- F / (c slip)) oscillates without damping
        let slope = if re > 1e-12 {
            let c2 = sc.drag2.factor[i] * sc.drag2.cd_re[i];
            ((c2 / (fh * cdre)).ln() / (1.0 + DRE).ln()).max(0.0)
        } else {
            0.0
        };
        let ux = state.uf[i] - state.up[i];
        let slip = sc.work[i];
        // the ratio before the square: ux^2 and slip^2 underflow to 0 (0/0) for a slip
        // below 1e-154 m/s, as the first implicit step of a lid-driven column leaves
        // deep under a fine grid (Couette at 133 cells and more)
        let along = if slip > 0.0 { (ux / slip).powi(2) } else { 0.0 };
        co.drag_tangent[i] = 1.0 + slope * along;
        // (w_r / slip)^2 = 1 - (ux / slip)^2: the slip is the hypotenuse of the two
        co.normal_tangent[i] = 1.0 + if slip > 0.0 { slope * (1.0 - along).max(0.0) } else { 0.0 };
        co.beta[i] = phi * cc;
        co.k_drag[i] = cc / eps;
        co.mobility[i] = eps * eps / cc;
        co.cd_ratio[i] = if cdre > 0.0 { cd_inf * re_h / cdre } else { 0.0 };
    }
}

/// Drift diffusivity of the fluctuation closure (Chassagne eqs 4.3-4.4) with the flow
/// scales and Reynolds stress of [`crate::inputs`], damped by the open fraction
/// (1 - phi/phi_max) of the cell.
///
/// Why the damping: the drift velocity is the drag of the fluid fluctuations seen by the
/// grains (eq 4.3); grains in enduring contact do not follow the eddies, the contact
/// network carries that drag. (1 - phi/phi_max) is the factor by which the Li & Sawamoto
/// mixing length (Chassagne eq 2.8b, Maurin eq 5) damps the eddies inside a bed: it is
/// 1 to within phi/phi_max in a dilute suspension (1e-3 in Cheng's dilute cases, so the
/// Rouse balance is untouched) and vanishes at the packing of the granular closure, so
/// that no eddy diffusivity of a turbulence closure (k-omega's start-up puts
/// nu_t = 0.15 m^2/s into a packed bed) can dissolve a packed bed.
fn evaluate_drift(params: &Params, state: &State, work: &mut Workspace) {
    let Some(fl) = params.m.fluctuation else { return };
    let g = params.op.grid();
    let bed = inputs::bed_surface(g.centres(), &state.phi, params.scene.domain.bed_height);
    let scales = inputs::flow_scales(g.centres(), g.dz(), &state.uf, g.height(), bed);
    let nu_t = state.eddy.values();
    for (i, &nt) in nu_t.iter().enumerate() {
        let (k, omega) = state.kw.as_ref().map_or((0.0, 0.0), |kw| (kw.col.k[i], kw.col.omega[i]));
        let reynolds_stress = inputs::reynolds_stress(nt, work.co.gamma_f[i]);
        work.sc.turbulence[i] = TurbulencePoint { k, omega, nu_t: nt, reynolds_stress };
    }
    fl.diffusivity_batch(&work.sc.turbulence, &scales, &mut work.co.drift);
    let phi_max = params.m.rheology.phi_max();
    for (d, &phi) in work.co.drift.iter_mut().zip(&state.phi) {
        *d = d.max(0.0) * (1.0 - phi / phi_max).clamp(0.0, 1.0);
    }
}

/// After the momentum step of a local rheology: the shear rates of the new u_p and the
/// pressure at them, so that the phi step balances the weight with the dilatancy
/// pressure of the shear rate the momentum step just produced (the analogue of the
/// kinetic path, whose phi step sees the new temperature). With the shear rate of the
/// start of the step instead, the momentum step of the next step sees a pressure off the
/// balance by (gamma_new / gamma_old)^2, and since mu(I) is flat (a stress-ratio error
/// of 0.4 % is an I error of 1.6 %) that loop amplifies: the profiles never settle.
pub(super) fn update_local_pressure(params: &Params, state: &State, work: &mut Workspace) {
    let Rheology::Local { model, elastic } = params.m.rheology else { return };
    shear_rates(params, state, work);
    local_pressures(params, state, work, model, elastic);
}
