//! k and omega of a two-equation turbulence closure in the Eulerian column (Cheng et al.
//! 2018 eqs 21-35), advanced by the shared [`crate::column::turbulence::KOmegaRun`].

use super::solver::{breakdown, Params, Workspace};
use super::state::State;
use crate::column::bdf2::Bdf2;
use crate::column::k_omega::Before;
use crate::run::Breakdown;

/// Backward-Euler (or, with `bdf2`, BDF2) step of k and omega with the shear rate of
/// the new fluid velocity; nothing without such a closure.
pub(super) fn solve_two_equation(
    params: &Params,
    state: &mut State,
    work: &mut Workspace,
    dt: f64,
    bdf2: Option<Bdf2>,
) -> Result<(), Breakdown> {
    let Some(model) = params.m.turbulence.as_two_equation() else { return Ok(()) };
    let top = params.fluid_top(&state.uf);
    params.op.shear_rate(&state.uf, top, &mut work.sc.shear);
    let Some(kw) = state.kw.as_mut() else { return Ok(()) };
    for ((d, &k), &phi) in kw.drag.iter_mut().zip(&work.co.k_drag).zip(&state.phi) {
        // beta of Cheng eq 23 = phi eps K / phi
        *d = k * (1.0 - phi.clamp(0.0, 1.0));
    }
    let (phi, uf, shear) = (&state.phi, &state.uf, &work.sc.shear);
    let p = &state.stepping.previous;
    let before = bdf2.map(|weights| Before { weights, k: &p.k, omega: &p.omega });
    let result =
        kw.advance(model, &params.op, &params.k_omega_physics, phi, uf, shear, work.co.visc_ratio[0], dt, before);
    result.map_err(|f| breakdown(params, state, f.cell, f.field, f.value, f.reason.into()))
}
