//! k and omega of a two-equation turbulence closure in the Eulerian column (Cheng et al.
//! 2018 eqs 21-35), advanced by the shared [`crate::column::turbulence::KOmegaRun`].

use super::Eulerian;
use crate::column::bdf2::Bdf2;
use crate::column::k_omega::Before;
use crate::run::Breakdown;

impl Eulerian<'_> {
    /// Backward-Euler (or, with `bdf2`, BDF2) step of k and omega with the shear rate of
    /// the new fluid velocity; nothing without such a closure.
    pub(super) fn solve_two_equation(&mut self, dt: f64, bdf2: Option<Bdf2>) -> Result<(), Breakdown> {
        let Some(model) = self.m.turbulence.as_two_equation() else { return Ok(()) };
        let top = self.fluid_top(&self.s.uf);
        self.op.shear_rate(&self.s.uf, top, &mut self.sc.shear);
        let Some(kw) = self.s.kw.as_mut() else { return Ok(()) };
        for ((d, &k), &phi) in kw.drag.iter_mut().zip(&self.co.k_drag).zip(&self.s.phi) {
            // beta of Cheng eq 23 = phi eps K / phi
            *d = k * (1.0 - phi.clamp(0.0, 1.0));
        }
        let (phi, uf, shear) = (&self.s.phi, &self.s.uf, &self.sc.shear);
        let p = &self.stepping.previous;
        let before = bdf2.map(|weights| Before { weights, k: &p.k, omega: &p.omega });
        let result =
            kw.advance(model, &self.op, &self.k_omega_physics, phi, uf, shear, self.co.visc_ratio[0], dt, before);
        result.map_err(|f| self.breakdown(f.cell, f.field, f.value, f.reason.into()))
    }
}
