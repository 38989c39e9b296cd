//! Particle pressure and shear stress of the Eulerian column: kinetic theory (Chassagne
//! et al. 2023 eqs 2.12-2.15, 2.19-2.23) or a local rheology (mu(I), mu(K): eqs 1.1-1.2
//! with the Johnson-Jackson elastic pressure, eq 2.14).

use saltus_core::{KineticTheory, LocalRheology, LocalState, SaltationInput};

use super::rheology::{coulomb, Elastic, Pressure, Rheology};
use super::solver::{Params, Workspace};
use super::state::State;

/// Step of the one-sided differences in phi of the pressure.
const DPHI: f64 = 1e-7;

/// The local state of a cell or face of shear rate `gamma` under the pressure `p`.
pub(super) fn local_state(params: &Params, gamma: f64, p: f64) -> LocalState {
    LocalState {
        shear_rate: gamma,
        pressure: p,
        diameter: params.c.d,
        particle_density: params.c.rho_p,
        fluid_viscosity: params.c.rho_f * params.c.nu_f,
    }
}

/// Particle pressure and stress at cells and faces from the current state.
pub(super) fn evaluate_stress(params: &Params, state: &State, work: &mut Workspace) {
    let n = state.len();
    let r = params.cfg.settings.shear_rate_regularisation;
    match params.m.rheology {
        Rheology::Kinetic { model: kt, elastic } => {
            kinetic_coefficients(params, state, work, kt, &elastic);
            let mu_s = kt.static_friction();
            let co = &mut work.co;
            for j in 0..=n {
                let (l, rr) = (j.saturating_sub(1), j.min(n - 1));
                let g = co.face_gamma[j];
                let eta = 0.5 * (co.eta_kin[l] + co.eta_kin[rr]);
                let p_el = 0.5 * (co.pres[l].p_el + co.pres[rr].p_el);
                let (tc, sec) = coulomb(mu_s * p_el, g, r);
                co.eta_face[j] = eta + sec;
                co.sigma_face[j] = 0.0;
                co.tau_p[j] = eta * g + tc;
            }
        }
        Rheology::Local { model, elastic } => {
            local_pressures(params, state, work, model, elastic);
            surface_overburden(params, state, work);
            // mu(X) at the face states: one batch of control numbers, one of friction
            for j in 0..=n {
                let (l, rr) = (j.saturating_sub(1), j.min(n - 1));
                let co = &work.co;
                let p = 0.5 * (co.pres[l].p + co.overburden[l] + co.pres[rr].p + co.overburden[rr]);
                work.sc.face_p[j] = p;
                work.sc.face_states[j] = local_state(params, co.face_gamma[j], p);
            }
            let sc = &mut work.sc;
            model.control_number_batch(&sc.face_states, &mut sc.face_x);
            model.eval_batch(&sc.face_x, &mut sc.face_mu, &mut sc.face_packing);
            for j in 0..=n {
                let (t0, sec) = coulomb(sc.face_mu[j] * sc.face_p[j], work.co.face_gamma[j], r);
                work.co.eta_face[j] = sec;
                work.co.sigma_face[j] = 0.0;
                work.co.tau_p[j] = t0;
            }
        }
    }
    work.co.tau_p[n] = 0.0;
    let h = params.op.spacing();
    for ((cond, &eta), &hj) in work.co.part_cond.iter_mut().zip(&work.co.eta_face).zip(h).take(n).skip(1) {
        *cond = eta / hj;
    }
}

/// Kinetic coefficients of every cell in one batch call (with the saltation input of
/// each cell when the closure corrects for saltation, eq 3.6), dF1/dphi by one batch
/// difference, and the pressure, viscosity and conductivity of eqs 2.19-2.21.
fn kinetic_coefficients(
    params: &Params,
    state: &State,
    work: &mut Workspace,
    kt: &dyn KineticTheory,
    elastic: &Elastic,
) {
    let n = state.len();
    let c = params.c;
    let salt = kt.saltation_enabled();
    let phi_max = kt.phi_max();
    let sc = &mut work.sc;
    for i in 0..n {
        let phi = state.phi[i].max(0.0);
        sc.phi_c[i] = phi;
        // dF1/dphi one-sided away from phi_max (F1 is convex and >= phi, so the slope
        // is >= F1/phi, the dilute limit 1); at phi_max the point is not used
        sc.phi_h[i] = if phi + DPHI < phi_max { phi + DPHI } else { phi };
        sc.salt[i] = SaltationInput {
            sqrt_t: state.temp[i].max(0.0).sqrt(),
            k_drag: work.co.k_drag[i],
            particle_density: c.rho_p,
            diameter: c.d,
        };
    }
    kt.coefficients_batch(&sc.phi_c, salt.then_some(&sc.salt[..]), &mut work.co.coef);
    kt.pressure_coefficient_batch(&sc.phi_h, &mut sc.f1_h);
    for i in 0..n {
        let phi = sc.phi_c[i];
        let co = work.co.coef[i];
        let f1p = if phi + DPHI < phi_max { (sc.f1_h[i] - co.f1) / DPHI } else { co.f1 / phi.max(1e-12) };
        work.co.f1_slope[i] = f1p.max(0.0);
        let st = sc.salt[i].sqrt_t;
        work.co.eta_kin[i] = kt.shear_viscosity(&co, c.rho_p, c.d, st);
        work.co.kappa[i] = kt.conductivity(&co, c.rho_p, c.d, st);
    }
    for (i, &phi) in sc.phi_c.iter().enumerate() {
        work.co.pres[i].p_el = elastic.pressure(phi);
        work.co.elastic_slope[i] = elastic.derivative(phi);
    }
    kinetic_pressures(params, state, work, kt);
}

/// Particle pressure of every cell at the current temperature, linearised in phi:
/// p_el + rho_p F1 T with slope p_el' + rho_p T F1' (eqs 2.14, 2.19). The elastic part
/// and the coefficients are those of [`kinetic_coefficients`]: phi is the same
/// until the phi step, so the temperature step reuses them.
pub(super) fn kinetic_pressures(params: &Params, state: &State, work: &mut Workspace, kt: &dyn KineticTheory) {
    let rho_p = params.c.rho_p;
    let co = &mut work.co;
    for (i, (&phi, &t)) in state.phi.iter().zip(&state.temp).enumerate() {
        let (phi, t) = (phi.max(0.0), t.max(0.0));
        let p_el = co.pres[i].p_el;
        let a = co.elastic_slope[i] + rho_p * t * co.f1_slope[i];
        let p = p_el + kt.kinetic_pressure(&co.coef[i], rho_p, t);
        co.pres[i] = Pressure { p, p_el, a, b: p - a * phi };
    }
}

/// Pressure of a local rheology at every cell from the current phi and the cell shear
/// rate of the current u_p, linearised in phi by one batch difference: elastic plus the
/// dilatancy pressure at which packing(X) = phi ([`Rheology::local_pressure`]).
pub(super) fn local_pressures(
    params: &Params,
    state: &State,
    work: &mut Workspace,
    model: &dyn LocalRheology,
    elastic: Elastic,
) {
    let n = state.len();
    for i in 0..n {
        let phi = state.phi[i].max(0.0);
        work.sc.phi_c[i] = phi;
        work.sc.phi_h[i] = phi + DPHI;
        work.sc.cell_states[i] = local_state(params, work.co.gamma_p[i], 0.0);
    }
    let sc = &mut work.sc;
    model.control_of_packing_batch(&sc.phi_c, &mut sc.cell_x);
    model.control_of_packing_batch(&sc.phi_h, &mut sc.cell_x_h);
    model.pressure_at_batch(&sc.cell_states, &sc.cell_x, &mut sc.cell_p);
    model.pressure_at_batch(&sc.cell_states, &sc.cell_x_h, &mut sc.cell_p_h);
    // no shear-induced pressure at or above the packing at zero shear (x = 0), nor where
    // it is not finite
    let shear = |x: f64, p: f64| if x > 0.0 && p.is_finite() { p } else { 0.0 };
    for i in 0..n {
        let phi = sc.phi_c[i];
        let p = elastic.pressure(phi) + shear(sc.cell_x[i], sc.cell_p[i]);
        let a = if phi + DPHI < elastic.phi_max {
            ((elastic.pressure(phi + DPHI) + shear(sc.cell_x_h[i], sc.cell_p_h[i]) - p) / DPHI).max(0.0)
        } else {
            elastic.derivative(phi)
        };
        let p_el = elastic.pressure(phi);
        work.co.pres[i] = Pressure { p, p_el, a, b: p - a * phi };
    }
}

/// Overburden of local rheologies: the weight the volume-fraction flux cannot bring into
/// the discrete wall-normal balance. The well-balanced flux makes each face carry
/// p_L - p_R = gw h (phi_L + phi_R)/2 at steady state, but at the free surface of a dense
/// layer the face between the last cell with grains and the empty cell above has no
/// grains upwind of the settling velocity: its flux vanishes whatever the imbalance
/// (r = 0 in `well_balanced_face`), and the dilatancy pressure of the partly filled
/// surface cell, evaluated as if its grains were spread over the cell, is far below the
/// weight of its upper half (0.22 Pa against 0.79 Pa in the dry incline at 100 cells).
/// The missing weight, gw h phi_c + p_R - p_L at such a face (weighted by 1 - r, so that
/// it fades where the flux can act and is zero at faces in balance), is added to the
/// pressure the momentum step sees in every cell below. It is constant below the face,
/// so the phi step, which sees pressure differences only, is unchanged.
fn surface_overburden(params: &Params, state: &State, work: &mut Workspace) {
    let n = state.len();
    let gw = params.c.buoyant_weight;
    let h = params.op.spacing();
    let mut sum = 0.0;
    work.co.overburden[n - 1] = 0.0;
    for j in (1..n).rev() {
        let (l, r) = (j - 1, j);
        let (phi_l, phi_r) = (state.phi[l].max(0.0), state.phi[r].max(0.0));
        let phi_c = 0.5 * (phi_l + phi_r);
        let (pl, pr) = (work.co.pres[l].p, work.co.pres[r].p);
        let force = gw * phi_c * h[j] + pr - pl;
        if phi_c > 0.0 && force > 0.0 && force.is_finite() {
            let (ratio, _) = super::volume_fraction::well_balanced_face(params, state, j, 1.0, gw, pl, pr);
            sum += (1.0 - ratio.min(1.0)).max(0.0) * force;
        }
        work.co.overburden[l] = sum;
    }
}
