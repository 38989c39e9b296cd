//! Streamwise momentum of both phases (Chassagne et al. 2023 eqs 2.3-2.4): one 2x2
//! block-tridiagonal backward-Euler (or BDF2) solve with the drag implicit, each phase's
//! diffusion and wall rows assembled by the shared [`crate::column::ColumnOperator`].
//!
//! BDF2 with a variable step is a backward-Euler row with the mass term scaled and the old
//! velocity replaced by a combination of the last two ([`crate::column::bdf2`]), so that
//! the same assembly serves both.

use super::block::BlockTridiagonal;
use super::config::Top;
use super::solver::{breakdown, Params, Workspace};
use super::state::State;
use super::PHI_FLOOR;
use crate::column::bdf2::Bdf2;
use crate::column::Band;
use crate::run::Breakdown;

/// One phase (0 fluid, 1 particles) of the block system, as a scalar band: the
/// off-diagonal blocks are diagonal, so each phase's transport is a tridiagonal band.
struct Phase<'a> {
    block: &'a mut BlockTridiagonal,
    c: usize,
}

impl Band for Phase<'_> {
    #[inline(always)]
    fn add(&mut self, row: usize, lower: f64, diag: f64, upper: f64, rhs: f64) {
        let c = self.c;
        self.block.lower[row][c] += lower;
        self.block.diag[row][c][c] += diag;
        self.block.upper[row][c] += upper;
        self.block.rhs[row][c] += rhs;
    }
}

/// Step `dt` of the coupled streamwise momentum of both phases under the pressure
/// gradient `grad` (Pa/m) of the end of the step: backward Euler, or BDF2 with the
/// velocities of the last two accepted states when `bdf2` holds the weights of this
/// step (the state then holds their extrapolation, [`Eulerian::extrapolate`]).
pub(super) fn solve_momentum(
    params: &Params,
    state: &mut State,
    work: &mut Workspace,
    dt: f64,
    grad: f64,
    bdf2: Option<Bdf2>,
) -> Result<(), Breakdown> {
    let n = state.len();
    let c = params.c;
    let inv_dt = 1.0 / dt;
    let dz = params.op.grid().dz();
    let (s, co) = (&*state, &work.co);
    let prev = &state.stepping.previous;
    let bl = &mut work.sc.block;
    for i in 0..n {
        let phi = s.phi[i].max(0.0);
        let eps = 1.0 - phi;
        let dz = dz[i];
        let phim = phi.max(PHI_FLOOR);
        // drag linearised about the old slip: beta_t (u_f - u_p) + (beta - beta_t) slip_old
        let tangent = co.drag_tangent[i];
        let bf = co.beta[i] * dz;
        let bp = phim * eps * co.k_drag[i] * dz;
        let slip = s.uf[i] - s.up[i];
        let (mut mf, mut mp) = (eps * c.rho_f * dz * inv_dt, phim * c.rho_p * dz * inv_dt);
        let (mut old_f, mut old_p) = (s.uf[i], s.up[i]);
        if let Some(b) = bdf2 {
            // the state holds the extrapolation about which the drag is linearised;
            // the old values are the two last accepted states
            old_f = b.old(work.saved.uf()[i], prev.uf[i]);
            old_p = b.old(work.saved.up()[i], prev.up[i]);
            mf *= b.scale();
            mp *= b.scale();
        }
        bl.diag[i] = [[mf + tangent * bf, -tangent * bf], [-tangent * bp, mp + tangent * bp]];
        bl.lower[i] = [0.0; 2];
        bl.upper[i] = [0.0; 2];
        bl.rhs[i] = [
            mf * old_f + eps * (c.rho_f * c.gx + grad) * dz + (tangent - 1.0) * bf * slip,
            mp * old_p + phim * (c.rho_p * c.gx + grad) * dz + co.sigma_face[i + 1]
                - co.sigma_face[i]
                - (tangent - 1.0) * bp * slip,
        ];
    }
    params.op.add_diffusion(&co.fluid_cond, &mut Phase { block: bl, c: 0 });
    params.op.add_diffusion(&co.part_cond, &mut Phase { block: bl, c: 1 });
    // bottom no-slip for both phases: stress = k du/dz at the wall
    params.op.add_wall(c.rho_f * co.fluid_k[0], &mut Phase { block: bl, c: 0 });
    params.op.add_wall(co.eta_face[0], &mut Phase { block: bl, c: 1 });
    if params.scene.domain.top == Top::Lid {
        let w = c.rho_f * co.fluid_k[n - 1];
        params.op.add_lid(w, params.scene.domain.lid_velocity, &mut Phase { block: bl, c: 0 });
    }
    if let Err(row) = bl.solve(&mut work.sc.xb) {
        return Err(breakdown(params, state, row, "u_f", f64::NAN, "singular momentum system".into()));
    }
    for i in 0..n {
        let [a, b] = work.sc.xb[i];
        if !a.is_finite() {
            return Err(breakdown(params, state, i, "u_f", a, "not finite after the momentum solve".into()));
        }
        if !b.is_finite() {
            return Err(breakdown(params, state, i, "u_p", b, "not finite after the momentum solve".into()));
        }
        state.uf[i] = a;
        state.up[i] = b;
    }
    Ok(())
}
