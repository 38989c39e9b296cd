//! The state of the Eulerian column: the fields that define the solution and the
//! counters of the run, with the copy a rejected step restores. Everything recomputed
//! from it lives in [`super::coefficients`].

use crate::column::turbulence::{EddyViscosity, KOmegaRun};

/// The solution: cell fields, face fluxes, the lagged eddy viscosity and the k and omega
/// of a two-equation closure, and the run counters.
pub(super) struct State {
    /// simulated time (s)
    pub time: f64,
    /// accepted steps
    pub steps: usize,
    /// rejected steps
    pub rejected: usize,
    /// steady residual of the last accepted step (1/s)
    pub residual: f64,
    /// solid volume fraction per cell
    pub phi: Vec<f64>,
    /// fluid and particle streamwise velocities per cell (m/s)
    pub uf: Vec<f64>,
    pub up: Vec<f64>,
    /// granular temperature per cell (m^2/s^2), zeros without kinetic theory
    pub temp: Vec<f64>,
    /// particle volume flux phi w_p through each face (m/s), faces 0..=n: the wall-normal
    /// slip of the next drag evaluation comes from it
    pub flux: Vec<f64>,
    /// the drift part of `flux` (m/s), zero without a fluctuation closure: the flux of the
    /// drift velocity, which is part of the slip the drag sees (Chassagne eq 4.3), not of
    /// the settling
    pub drift_flux: Vec<f64>,
    /// eddy viscosity, lagged and relaxed between steps (Picard)
    pub eddy: EddyViscosity,
    /// k and omega, present only when the turbulence closure transports them
    pub kw: Option<KOmegaRun>,
    /// initial sediment height sum phi dz (m)
    pub mass0: f64,
    /// the step to take next and the fields one step back
    pub stepping: Stepping,
}

/// Adaptive stepping between accepted steps.
pub(super) struct Stepping {
    /// next time step (s)
    pub dt: f64,
    /// consecutive steps under the steady tolerance
    pub calm: usize,
    /// time-accurate stepping: the fields before the last accepted step and its
    /// length (s), 0 before the first (that step is then backward Euler)
    pub previous: Previous,
}

/// The transported fields one accepted step back, for BDF2.
#[derive(Default)]
pub(super) struct Previous {
    pub uf: Vec<f64>,
    pub up: Vec<f64>,
    pub phi: Vec<f64>,
    pub temp: Vec<f64>,
    /// k and omega, empty without a two-equation closure
    pub k: Vec<f64>,
    pub omega: Vec<f64>,
    /// the particle flux and its drift part at the faces
    pub flux: Vec<f64>,
    pub drift_flux: Vec<f64>,
    /// length of the step that followed them (s); 0: none yet
    pub dt: f64,
}

/// The fields of [`State`] a rejected step restores (nu_t is a relaxation lag, not
/// restored: the retry relaxes it once more, as every attempt does).
#[derive(Default)]
pub(super) struct Saved {
    phi: Vec<f64>,
    uf: Vec<f64>,
    up: Vec<f64>,
    temp: Vec<f64>,
    flux: Vec<f64>,
    drift_flux: Vec<f64>,
}

impl Saved {
    /// The fluid velocity saved (m/s).
    pub fn uf(&self) -> &[f64] {
        &self.uf
    }
    /// The particle velocity saved (m/s).
    pub fn up(&self) -> &[f64] {
        &self.up
    }
    /// The volume fraction saved.
    pub fn phi(&self) -> &[f64] {
        &self.phi
    }
    /// The granular temperature saved (m^2/s^2).
    pub fn temp(&self) -> &[f64] {
        &self.temp
    }
    /// The particle flux saved (m/s).
    pub fn flux(&self) -> &[f64] {
        &self.flux
    }
    /// The drift part of the particle flux saved (m/s).
    pub fn drift_flux(&self) -> &[f64] {
        &self.drift_flux
    }
}

impl State {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.phi.len()
    }

    /// Sediment height sum phi dz (m).
    pub fn sediment_height(&self, dz: &[f64]) -> f64 {
        self.phi.iter().zip(dz).map(|(p, h)| p * h).sum()
    }

    /// Copy the fields a rejection restores into `saved`.
    pub fn save(&mut self, saved: &mut Saved) {
        if let Some(kw) = &mut self.kw {
            kw.col.save();
        }
        for (dst, src) in [
            (&mut saved.phi, &self.phi),
            (&mut saved.uf, &self.uf),
            (&mut saved.up, &self.up),
            (&mut saved.temp, &self.temp),
            (&mut saved.flux, &self.flux),
            (&mut saved.drift_flux, &self.drift_flux),
        ] {
            dst.clear();
            dst.extend_from_slice(src);
        }
    }

    /// Restore the fields of the last [`State::save`].
    pub fn restore(&mut self, saved: &Saved) {
        if let Some(kw) = &mut self.kw {
            kw.col.restore();
        }
        self.phi.copy_from_slice(&saved.phi);
        self.uf.copy_from_slice(&saved.uf);
        self.up.copy_from_slice(&saved.up);
        self.temp.copy_from_slice(&saved.temp);
        self.flux.copy_from_slice(&saved.flux);
        self.drift_flux.copy_from_slice(&saved.drift_flux);
    }

    /// Largest relative rate of change (1/s) since `saved` over a step `dt`, and the
    /// factor by which dt may grow. Particle fields are weighted by phi (changes of
    /// phi u_p and phi T relative to their maxima), so that the velocity and temperature of
    /// the vanishing particles of the clear-fluid region, which carry nothing, do not hold
    /// the run away from steady state. The growth aims at phi changes of half
    /// `max_phi_change` and relative changes of `field_change` per step; with `phi_only`
    /// (time-accurate stepping, whose time error is set by the largest step) at the phi
    /// changes alone.
    pub fn rates(
        &self,
        saved: &Saved,
        dt: f64,
        kinetic: bool,
        max_phi_change: f64,
        field_change: f64,
        phi_only: bool,
    ) -> (f64, f64) {
        let mut du: f64 = 0.0;
        let mut dq: f64 = 0.0;
        let mut de: f64 = 0.0;
        let mut dphi: f64 = 0.0;
        let (mut umax, mut qmax, mut emax, mut phimax) = (1e-300f64, 1e-300f64, 1e-300f64, 1e-300f64);
        for i in 0..self.len() {
            let phi = self.phi[i].max(0.0);
            du = du.max((self.uf[i] - saved.uf[i]).abs());
            dq = dq.max(phi * (self.up[i] - saved.up[i]).abs());
            de = de.max(phi * (self.temp[i] - saved.temp[i]).abs());
            dphi = dphi.max((self.phi[i] - saved.phi[i]).abs());
            umax = umax.max(self.uf[i].abs());
            qmax = qmax.max(phi * self.up[i].abs());
            emax = emax.max(phi * self.temp[i]);
            phimax = phimax.max(phi);
        }
        let mut rel = (du / umax).max(dphi / phimax);
        if let Some(kw) = &self.kw {
            rel = rel.max(kw.change());
        }
        if qmax > 1e-300 {
            rel = rel.max(dq / qmax);
        }
        if kinetic {
            rel = rel.max(de / emax);
        }
        let by_phi = 0.5 * max_phi_change / dphi.max(1e-300);
        let target = if phi_only { by_phi } else { by_phi.min(field_change / rel.max(1e-300)) };
        (rel / dt, target.clamp(0.5, 1.3))
    }
}
