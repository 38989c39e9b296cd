//! Granular temperature (Chassagne et al. 2023 eq 2.16 with the flux 2.18, coefficients
//! 2.19-2.23 and the drag dissipation 2.25 or 3.13), kinetic closures only.

use super::rheology::Rheology;
use super::solver::{breakdown, Params, Workspace};
use super::state::State;
use super::PHI_FLOOR;
use crate::column::bdf2::Bdf2;
use crate::run::Breakdown;

/// Backward-Euler step of the granular temperature: production from the shear rate of
/// the new u_p (the column operator's, exact on stretched grids), conduction,
/// collisional and drag dissipation implicit, so T stays >= 0. With `bdf2`, a BDF2 step
/// ([`Bdf2::positive_row`]) from the last two accepted states, with the coefficients
/// and the dissipation rate per unit T of the state, which then holds their
/// extrapolation to the end of the step ([`Eulerian::extrapolate`]).
pub(super) fn solve_temperature(
    params: &Params,
    state: &mut State,
    work: &mut Workspace,
    dt: f64,
    bdf2: Option<Bdf2>,
) -> Result<(), Breakdown> {
    let Rheology::Kinetic { model: kt, .. } = params.m.rheology else { return Ok(()) };
    let n = state.len();
    let c = params.c;
    let top = params.op.stress_free_shear_top(&state.up);
    params.op.shear_rate(&state.up, top, &mut work.co.gamma_p);
    let dz = params.op.grid().dz();
    let h = params.op.spacing();
    let cd_inf = params.m.drag.cd_inf();
    let (s, co) = (&*state, &work.co);
    let (t_now, t_before) = (work.saved.temp(), &state.stepping.previous.temp);
    for (cd, &r) in work.sc.cd.iter_mut().zip(&co.cd_ratio) {
        *cd = cd_inf / r.max(1e-300);
    }
    kt.drag_dissipation_batch(cd_inf, &work.sc.cd, &mut work.sc.c_j);
    let t = &mut work.sc.tri;
    for (i, &dzi) in dz.iter().enumerate() {
        let phi = s.phi[i].max(0.0);
        let now = s.temp[i].max(0.0);
        let (scale, old) = match bdf2 {
            Some(b) => b.positive_row(t_now[i].max(0.0), t_before[i]),
            None => (1.0, now),
        };
        let m = scale * 1.5 * c.rho_p * phi.max(PHI_FLOOR) * dzi / dt;
        let sink = kt.dissipation_per_temperature(&co.coef[i], c.rho_p, c.d, now.sqrt()) + work.sc.c_j[i] * co.beta[i];
        let prod = co.eta_kin[i] * co.gamma_p[i] * co.gamma_p[i];
        t.lower[i] = 0.0;
        t.upper[i] = 0.0;
        t.diag[i] = m + sink * dzi;
        t.rhs[i] = m * old + prod * dzi;
    }
    for (j, &hj) in h.iter().enumerate().take(n).skip(1) {
        let k = 0.5 * (co.kappa[j - 1] + co.kappa[j]) / hj;
        t.diag[j - 1] += k;
        t.upper[j - 1] -= k;
        t.diag[j] += k;
        t.lower[j] -= k;
    }
    if let Err(row) = t.solve(&mut work.sc.work) {
        return Err(breakdown(params, state, row, "theta_g", f64::NAN, "singular temperature system".into()));
    }
    for i in 0..n {
        let v = work.sc.work[i];
        if !(v.is_finite() && v >= -1e-300) {
            return Err(breakdown(
                params,
                state,
                i,
                "theta_g",
                v,
                "granular temperature not finite or negative".into(),
            ));
        }
        state.temp[i] = v.max(0.0);
    }
    Ok(())
}
