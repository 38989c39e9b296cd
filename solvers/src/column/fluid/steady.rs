//! The column's steady state: Picard iteration on nu_t for algebraic closures, pseudo-time
//! marching of k and omega for a two-equation model ([`FluidColumn::solve_steady`]).

use saltus_core::closure::turbulence::TwoEquation;

use super::super::params::{Closures, Coupling, SteadyReport};
use super::super::ColumnError;
use super::FluidColumn;

/// Pseudo-time step of k and omega in [`FluidColumn::solve_steady`] in units of the
/// turbulent time scale H / u*: first step and cap. The momentum is solved to steady state
/// with the lagged nu_t at every iteration; steps much longer than ~10 H/u* make the lag
/// oscillate (the Eulerian channel stalls at 1000 s = 1500 H/u*).
const PSEUDO_DT_FIRST: f64 = 0.01;
const PSEUDO_DT_CAP: f64 = 10.0;

impl FluidColumn {
    /// Solve the steady equation by Picard iteration on nu_t with under-relaxation
    /// [`ColumnParams::relaxation`](super::super::params::ColumnParams::relaxation) and infinite pseudo time step (the implicit operator
    /// with the no-slip wall is non-singular). Each iteration evaluates nu_t from the
    /// current velocity, checks the residual of the steady equation with that nu_t
    /// against `tol` (see [`FluidColumn::residual`]), and otherwise relaxes nu_t and
    /// solves the linear system. Starts from the current velocity; a laminar problem
    /// converges after one solve. Time is not advanced.
    ///
    /// On non-convergence after `max_iter` solves, returns
    /// [`ColumnError::NotConverged`]; the column keeps its last iterate.
    pub fn solve_steady(
        &mut self,
        coupling: &Coupling<'_>,
        closures: &Closures<'_>,
        tol: f64,
        max_iter: usize,
    ) -> Result<SteadyReport, ColumnError> {
        self.load_inputs(coupling, closures)?;
        if let Some(model) = closures.turbulence.as_two_equation() {
            return self.solve_steady_two_equation(model, closures, tol, max_iter);
        }
        let mut it = 0;
        loop {
            if let Some(done) = self.steady_check(closures, None, tol, it, max_iter)? {
                return Ok(done);
            }
            self.eddy.relax_from_previous();
            self.update_coefficients();
            self.solve_linear(f64::INFINITY, self.time, None)?;
            self.update_faces();
            it += 1;
        }
    }

    /// The head of every steady iteration after `it` solves: nu_t of the current state
    /// (the previous one kept for relaxation), the side-wall friction, the coefficients and
    /// the stresses, then the verdict on the momentum residual, or on the larger of it and
    /// `change` when the caller measures a change of its own. `Some` report when it is
    /// <= `tol`, [`ColumnError::NotConverged`] after `max_iter` solves, `None` to go on.
    fn steady_check(
        &mut self,
        closures: &Closures<'_>,
        change: Option<f64>,
        tol: f64,
        it: usize,
        max_iter: usize,
    ) -> Result<Option<SteadyReport>, ColumnError> {
        self.evaluate_turbulence(closures.turbulence)?;
        self.update_side_walls(closures.wall_friction);
        // nu_t <- nu_t(u), keeping the previous one
        self.eddy.take_candidate();
        self.update_coefficients();
        self.update_stresses();
        // without a change of the caller's the residual alone decides, and a NaN never converges
        let worst = change.map_or(self.residual, |c| self.residual.max(c));
        if worst <= tol {
            return Ok(Some(SteadyReport { iterations: it, residual: worst }));
        }
        if it == max_iter {
            return Err(ColumnError::NotConverged { iterations: it, residual: worst, tol });
        }
        Ok(None)
    }

    /// Steady state with a two-equation closure: every iteration solves the momentum to
    /// steady state with nu_t of the current k and omega, then advances k and omega by a
    /// pseudo-time step growing from 0.01 to 10 H/u*; converged when the momentum residual
    /// and the largest change of k per iteration relative to its maximum are both <= `tol`.
    fn solve_steady_two_equation(
        &mut self,
        model: &dyn TwoEquation,
        closures: &Closures<'_>,
        tol: f64,
        max_iter: usize,
    ) -> Result<SteadyReport, ColumnError> {
        let scale = self.turbulent_time_scale();
        let mut dt = PSEUDO_DT_FIRST * scale;
        let mut change = f64::INFINITY;
        let mut it = 0;
        loop {
            if let Some(done) = self.steady_check(closures, Some(change), tol, it, max_iter)? {
                return Ok(done);
            }
            self.solve_linear(f64::INFINITY, self.time, None)?;
            self.update_faces();
            let kw = self.kw.as_mut().ok_or(ColumnError::Unsupported { model: closures.turbulence.name() })?;
            kw.col.save();
            self.advance_two_equation(model, dt, self.time)?;
            if let Some(kw) = &self.kw {
                change = kw.change();
            }
            dt = (dt * 1.2).min(PSEUDO_DT_CAP * scale);
            it += 1;
        }
    }
}
