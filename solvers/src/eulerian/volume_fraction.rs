//! Sediment mass (Chassagne et al. 2023 eq 2.2) with the wall-normal particle flux of the
//! quasi-static wall-normal momentum balances (eqs 2.5-2.6): conservative, implicit in
//! phi, well balanced at steady state.

use saltus_core::DriftForm;

use super::rheology::Rheology;
use super::solver::{breakdown, Params, Workspace};
use super::state::State;
use super::workspace::Coefficients;
use crate::column::bdf2::Bdf2;
use crate::run::Breakdown;

/// minmod limiter: the smaller slope when both have the same sign, else 0.
#[inline]
fn minmod(a: f64, b: f64) -> f64 {
    if a * b <= 0.0 {
        0.0
    } else if a.abs() < b.abs() {
        a
    } else {
        b
    }
}

/// Implicit step of the sediment mass (eq 2.2) with the wall-normal particle velocity of
/// the quasi-static wall-normal momentum balance (eqs 2.5-2.6):
/// phi w_p = -(eps/K) [phi (rho_p - rho_f) g cos + dp_p/dz] - eps D dphi/dz, or
/// - eps d(D phi)/dz for a fluctuation closure of [`DriftForm::Ito`].
///
/// The face flux takes the grains' volume fraction from the cell upwind of the
/// settling and their mobility eps/K from the cell downwind: F = -m(phi_down) gw
/// phi_up, the first-order flux of Lagrangian-remap schemes for kinematic flows
/// phi v(phi) with v decreasing (the density upstream, the velocity downstream). Why: the settling flux f = phi m(phi) gw
/// of Kynch's theory falls with phi above phi = 1/(n + 1) (0.24 for a Richardson-Zaki
/// exponent n = 3.15), where its characteristics go upwards; a flux taking both phi
/// and m from the upper cell, f(phi_up), then grows an odd-even pattern in a
/// concentrated suspension (cells alternating between 0.57 and 0.03 in the batch
/// sedimentation of Pham Van Bang et al. 2008). This flux falls with phi_down and
/// grows with phi_up whatever the sign of f', so the scheme is monotone on both
/// branches. At steady state the bracket of the wall-normal balance vanishes and the
/// mobility cancels: steady states do not depend on which cell lends it.
///
/// With `bdf2`, a BDF2 step ([`crate::column::bdf2`]) from the state extrapolated to the
/// end of the step, about which the fluxes are linearised (the stepper puts it in the
/// state, [`Eulerian::extrapolate`]): the mass term scaled by s, the old phi the
/// combination a phi^n - b phi^{n-1} of the two last accepted states, and in the delta
/// form about the extrapolated phi* the right side gains -m s (phi* - old). The weights
/// sum to one, so the sediment mass is kept to round-off as in backward Euler.
pub(super) fn solve_phi(
    params: &Params,
    state: &mut State,
    work: &mut Workspace,
    dt: f64,
    bdf2: Option<Bdf2>,
) -> Result<(), Breakdown> {
    let n = state.len();
    let gw = params.c.buoyant_weight;
    let (hs, dz) = (params.op.spacing(), params.op.grid().dz());
    // local rheologies: the well-balanced deferred correction (see
    // `well_balanced_face`); kinetic theory keeps the MUSCL one
    let well_balanced = matches!(params.m.rheology, Rheology::Local { .. });
    // face coefficients: F_j = cl phi_L + cr phi_R + s
    let mut coeffs = std::mem::take(&mut work.sc.face_coeffs);
    coeffs.clear();
    coeffs.resize(3 * (n + 1), 0.0);
    for j in 1..n {
        let (l, r) = (j - 1, j);
        let h = hs[j];
        // the grains' volume fraction from the cell upwind of the settling (`up`), their
        // mobility from the cell downwind (`down`): see `solve_phi`'s doc
        let (up, down) = if gw >= 0.0 { (r, l) } else { (l, r) };
        let m = work.co.mobility[down];
        // drift flux -eps D dphi/dz (gradient) or -eps d(D phi)/dz (Ito), implicit in phi
        // with eps and D lagged: both keep the M-matrix (cl >= 0 >= cr), so the drift
        // costs no time-step restriction however large D is
        let (dl, dr) = match params.drift_form {
            DriftForm::Gradient => {
                let dd = 0.5 * ((1.0 - state.phi[l]) * work.co.drift[l] + (1.0 - state.phi[r]) * work.co.drift[r]);
                (dd, dd)
            }
            DriftForm::Ito => {
                let eps = 1.0 - 0.5 * (state.phi[l] + state.phi[r]);
                (eps * work.co.drift[l], eps * work.co.drift[r])
            }
        };
        let (pl, pr) = (work.co.pres[l], work.co.pres[r]);
        // local rheologies: factor r on the pressure part of the flux and the deferred
        // correction of the weight; kinetic theory: r = 1 and the MUSCL correction below
        let wb = if well_balanced { Some(well_balanced_face(params, state, j, m, gw, pl.p, pr.p)) } else { None };
        // Newton step of the wall-normal drag (see `settling_newton`): the mobility of the
        // lagged slip divided by the drag's tangent, plus the old settling velocity carried
        // upwind, implicit, with the weight 1 - 1/t
        let (t, w0) = settling_newton(state, &work.co, j, down);
        let mg = m / t;
        let mp = mg * wb.map_or(1.0, |w| w.0);
        work.sc.drift_lr[2 * j] = dl;
        work.sc.drift_lr[2 * j + 1] = dr;
        let mut cl = mp * pl.a / h + dl / h;
        let mut cr = -mp * pr.a / h - dr / h;
        if up == r {
            cr -= mg * gw;
        } else {
            cl -= mg * gw;
        }
        let carried = (1.0 - 1.0 / t) * w0;
        if carried < 0.0 {
            cr += carried;
        } else {
            cl += carried;
        }
        // second-order settling at steady state: the implicit upwind value plus a
        // deferred MUSCL correction with the minmod limiter (zero at an interface with
        // clear fluid, so phi stays >= 0); the steady balance is then
        // dp/dz = -phi_face (rho_p - rho_f) g cos to second order
        let (down, upv, beyond) = if up == r {
            (state.phi[l], state.phi[r], if r + 1 < n { state.phi[r + 1] } else { state.phi[r] })
        } else {
            (state.phi[r], state.phi[l], if l > 0 { state.phi[l - 1] } else { state.phi[l] })
        };
        let correction = 0.5 * minmod(down - upv, upv - beyond);
        let deferred = wb.map_or(-mg * gw * correction, |w| w.1 / t);
        coeffs[3 * j] = cl;
        coeffs[3 * j + 1] = cr;
        coeffs[3 * j + 2] = -mp * (pr.b - pl.b) / h + deferred;
    }
    let t = &mut work.sc.tri;
    // the BDF2 row's mass factor and old phi (backward Euler: 1 and the state's phi)
    let scale = bdf2.map_or(1.0, |b| b.scale());
    let mut old = std::mem::take(&mut work.sc.old_phi);
    old.clear();
    match bdf2 {
        Some(b) => old.extend(work.saved.phi().iter().zip(&state.stepping.previous.phi).map(|(&a, &p)| b.old(a, p))),
        None => old.extend_from_slice(&state.phi),
    }
    for i in 0..n {
        let m = scale * dz[i] / dt;
        let (cl_up, cr_up, s_up) = (coeffs[3 * (i + 1)], coeffs[3 * (i + 1) + 1], coeffs[3 * (i + 1) + 2]);
        let (cl_dn, cr_dn, s_dn) = (coeffs[3 * i], coeffs[3 * i + 1], coeffs[3 * i + 2]);
        t.diag[i] = m + cl_up - cr_dn;
        t.upper[i] = cr_up;
        t.lower[i] = -cl_dn;
        // delta form: the right side is minus the divergence of the fluxes at the old
        // phi, a telescoping sum, so the mass change is round-off of the increment
        let f_up = cl_up * state.phi[i] + if i + 1 < n { cr_up * state.phi[i + 1] } else { 0.0 } + s_up;
        let f_dn = if i > 0 { cl_dn * state.phi[i - 1] } else { 0.0 } + cr_dn * state.phi[i] + s_dn;
        t.rhs[i] = f_dn - f_up;
        if bdf2.is_some() {
            t.rhs[i] -= m * (state.phi[i] - old[i]);
        }
    }
    if let Err(row) = t.solve(&mut work.sc.work) {
        work.sc.face_coeffs = coeffs;
        work.sc.old_phi = old;
        return Err(breakdown(params, state, row, "phi", f64::NAN, "singular volume-fraction system".into()));
    }
    // fluxes of the implicit solution, then phi rebuilt from them in flux form: the
    // same solution up to the round-off of the solve, but the mass changes only by the
    // round-off of a telescoping sum, however ill-conditioned the stiff system is
    for i in 0..n {
        work.sc.work[i] += state.phi[i];
    }
    state.flux[0] = 0.0;
    state.flux[n] = 0.0;
    for j in 1..n {
        state.flux[j] = coeffs[3 * j] * work.sc.work[j - 1] + coeffs[3 * j + 1] * work.sc.work[j] + coeffs[3 * j + 2];
    }
    for (i, &dzi) in dz.iter().enumerate() {
        work.sc.work[i] = old[i] - dt / (scale * dzi) * (state.flux[i + 1] - state.flux[i]);
    }
    if params.m.fluctuation.is_some() {
        // the drift part of the flux of the new phi, as the flux itself
        for (j, &h) in hs.iter().enumerate().take(n).skip(1) {
            let (dl, dr) = (work.sc.drift_lr[2 * j], work.sc.drift_lr[2 * j + 1]);
            state.drift_flux[j] = (dl * work.sc.work[j - 1] - dr * work.sc.work[j]) / h;
        }
    }
    let phi_max = params.m.rheology.phi_max();
    for i in 0..n {
        let v = work.sc.work[i];
        let bad = if !v.is_finite() {
            Some("not finite")
        } else if v < -1e-9 {
            Some("negative")
        } else if v >= phi_max {
            Some("at or above the maximum packing of the granular closure")
        } else if (v - if bdf2.is_some() { work.saved.phi()[i] } else { state.phi[i] }).abs()
            > params.cfg.settings.max_phi_change
        {
            Some("changed more than solver.eulerian.max_phi_change in one step")
        } else {
            None
        };
        if let Some(reason) = bad {
            work.sc.face_coeffs = coeffs;
            work.sc.old_phi = old;
            return Err(breakdown(params, state, i, "phi", v, reason.into()));
        }
    }
    state.phi.copy_from_slice(&work.sc.work);
    work.sc.face_coeffs = coeffs;
    work.sc.old_phi = old;
    Ok(())
}

/// Newton linearisation of the wall-normal drag at interior face `j` whose mobility is
/// that of cell `cell` (downwind of the settling, see `solve_phi`): returns the tangent t of the drag in the wall-normal slip
/// (1 + d ln C / d ln Re (w_r / |slip|)^2, >= 1) and the old settling velocity w0 of the
/// face (the non-drift flux over its upwind phi, m/s).
///
/// Why: the quasi-static wall-normal balance (Chassagne 2023 eqs 2.5-2.6) sets the
/// settling velocity w through K(|slip|) w = force, and K depends on w through the slip
/// (eq 2.10, the full slip u_f - u_p + u_d of eq 4.3). With K lagged (Picard), the step
/// solves w_(n+1) = force / K(w_n): for a quadratic drag w_(n+1) w_n = w_s^2, a period-2
/// oscillation that never damps whatever the time step (the map's slope is
/// -d ln K / d ln Re, -0.5 to -1 at the Re ~ 300 of 3 mm grains). The suspended grains of
/// the Revil-Baudard sheet flows held such a cycle (settling velocity alternating
/// between 0.08 and 0.11 m/s step by step, residual 2 /s). Newton's step,
/// w = w0 + (force / K(w0) - w0) / t, converges quadratically; as a flux it is the
/// Picard flux over t plus (1 - 1/t) w0 phi_upwind, implicit upwind in phi, so the
/// matrix stays an M-matrix. At steady state w = w0 and the flux is the Picard one: the
/// steady state (and the well-balanced bed, where w0 = 0) is unchanged.
fn settling_newton(state: &State, co: &Coefficients, j: usize, cell: usize) -> (f64, f64) {
    let t = co.normal_tangent[cell];
    let settling = state.flux[j] - state.drift_flux[j];
    let donor = if settling < 0.0 { state.phi[j] } else { state.phi[j - 1] };
    let w0 = if donor > 0.0 && t > 1.0 { settling / donor } else { 0.0 };
    (t, if w0.is_finite() { w0 } else { 0.0 })
}

/// Well-balanced volume-fraction flux of local rheologies at interior face `j`, from the
/// old state: the factor r on the pressure part of the implicit flux and the deferred
/// correction of its weight. The flux of the wall-normal balance (Chassagne 2023 eqs
/// 2.5-2.6) is written with the weight of the central volume fraction
/// phi_c = (phi_L + phi_R)/2, carried at the velocity w = -m [gw phi_c + dp/dz] / phi_c
/// and transported with the MUSCL (minmod) value phi_w of phi upwind of w:
///   F = w phi_w = -m [gw phi_w + r dp/dz],  r = phi_w / phi_c,
/// with r and phi_w frozen over the step, dp/dz implicit (linearised in phi) and the
/// weight as the implicit upwind -m gw phi_up plus the deferred -m gw (phi_w - phi_up).
/// At steady state w = 0, so the discrete balance is the central one,
/// p_R - p_L = -gw h (phi_L + phi_R)/2, whose sum makes the pressure at each cell centre
/// exactly the weight above it whatever the shape of phi ("well balanced", as the
/// hydrostatic reconstruction of Audusse et al. 2004 for shallow water). The MUSCL
/// correction of the weight alone limits phi_face towards the upper cell across the free
/// surface of a dense layer, where phi drops from 0.55 to 0 in two cells; the steady
/// pressure under it then misses part of the weight of the surface cells (0.7 Pa of 236
/// in the dry incline at 100 cells), a first-order error that the flat mu(I) turns into
/// four times as large an error of the shear rate over the whole layer. Where the
/// pressure gradient vanishes (dilute settling) w = -m gw, phi_w is the MUSCL value of
/// the upper cell and the flux is the MUSCL one exactly. Returns (r, deferred flux).
pub(super) fn well_balanced_face(
    params: &Params,
    state: &State,
    j: usize,
    m: f64,
    gw: f64,
    pl: f64,
    pr: f64,
) -> (f64, f64) {
    let n = state.len();
    let (l, r) = (j - 1, j);
    let (phi_l, phi_r) = (state.phi[l].max(0.0), state.phi[r].max(0.0));
    let phi_c = 0.5 * (phi_l + phi_r);
    let force = gw * phi_c + (pr - pl) / params.op.spacing()[j];
    if !(phi_c > 0.0 && force.is_finite()) {
        // no grains on either side (or an infinite pressure, which the phi step then
        // rejects): the upwind flux
        return (1.0, 0.0);
    }
    let up_g = if gw >= 0.0 { phi_r } else { phi_l };
    // MUSCL value upwind of w: the upper cell when force > 0 (w < 0, downwards)
    let phi_w = if force > 0.0 {
        let beyond = if r + 1 < n { state.phi[r + 1] } else { phi_r };
        phi_r + 0.5 * minmod(phi_l - phi_r, phi_r - beyond)
    } else {
        let beyond = if l > 0 { state.phi[l - 1] } else { phi_l };
        phi_l + 0.5 * minmod(phi_r - phi_l, phi_l - beyond)
    };
    (phi_w / phi_c, -m * gw * (phi_w - up_g))
}
