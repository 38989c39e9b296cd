//! Turbulence of a column, written once for both solvers: the friction velocity of the
//! driving, the eddy viscosity with its one relaxation policy, and the inputs and step of
//! the k and omega of a two-equation closure.

use saltus_core::closure::turbulence::{TwoEquation, TwoEquationInput};
use saltus_core::{ColumnView, Turbulence};

use super::k_omega::{Before, ColumnGeometry, KOmegaColumn, TransportFailure};
use super::operator::ColumnOperator;

/// Friction velocity of the driving over a flow of depth `depth` (m/s):
/// u* = sqrt(max(g sin(alpha) + G_x / rho_f, 0) depth), the shear stress at the bed
/// surface of a clear-water flow in equilibrium with its driving `drive` (m/s^2). The
/// depth is the fluid above the bed (the water depth of the Eulerian scene, the whole
/// column for clear water): the stress at the bed surface is carried by that fluid only.
/// It sets the rough-wall and in-bed omega of a two-equation closure (Cheng et al. 2018
/// eq 34) and its initial state.
pub fn friction_velocity(drive: f64, depth: f64) -> f64 {
    (drive.max(0.0) * depth).sqrt()
}

/// The eddy viscosity nu_t of a column and its one relaxation policy: each evaluation of
/// the closure gives a candidate nu_t(u), and the column takes
/// nu_t <- w nu_t(u) + (1 - w) nu_t with w the relaxation (the candidate alone at the
/// first evaluation). Relaxing a lagged nu_t is a Picard iteration; w = 0.5 turns the map
/// of a fully turbulent mixing-length layer (nu_t <- C / nu_t, which oscillates with
/// w = 1) into a Newton (Babylonian) one, and it does not change a steady state.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct EddyViscosity {
    nu_t: Vec<f64>,
    candidate: Vec<f64>,
    relaxation: f64,
}

impl EddyViscosity {
    /// Zero nu_t over `n` cells with relaxation `w` in (0, 1].
    pub fn new(n: usize, relaxation: f64) -> Self {
        Self { nu_t: vec![0.0; n], candidate: vec![0.0; n], relaxation }
    }

    /// nu_t per cell (m^2/s).
    pub fn values(&self) -> &[f64] {
        &self.nu_t
    }

    /// The relaxation w.
    pub fn relaxation(&self) -> f64 {
        self.relaxation
    }

    /// Evaluate the closure on `col` into the candidate. A candidate that is not finite
    /// and >= 0 names its first bad cell.
    pub fn evaluate(&mut self, turbulence: &dyn Turbulence, col: &ColumnView<'_>) -> Result<(), usize> {
        turbulence.eddy_viscosity(col, &mut self.candidate);
        match self.candidate.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            Some(i) => Err(i),
            None => Ok(()),
        }
    }

    /// Take the candidate with the relaxation, or alone when `first`.
    pub fn relax(&mut self, first: bool) {
        let w = if first { 1.0 } else { self.relaxation };
        for (nt, &new) in self.nu_t.iter_mut().zip(&self.candidate) {
            *nt = w * new + (1.0 - w) * *nt;
        }
    }

    /// Take the candidate unrelaxed, keeping the previous nu_t as the candidate (a steady
    /// Picard iteration measures its residual with the unrelaxed nu_t, then calls
    /// [`EddyViscosity::relax_from_previous`]).
    pub fn take_candidate(&mut self) {
        std::mem::swap(&mut self.nu_t, &mut self.candidate);
    }

    /// After [`EddyViscosity::take_candidate`]: nu_t <- w nu_t + (1 - w) previous.
    pub fn relax_from_previous(&mut self) {
        let w = self.relaxation;
        for (new, &old) in self.nu_t.iter_mut().zip(&self.candidate) {
            *new = w * *new + (1.0 - w) * old;
        }
    }
}

/// The physical inputs of a two-equation closure that do not change along a run.
#[derive(Clone, Copy, Debug)]
pub struct KOmegaPhysics {
    /// clear-fluid kinematic viscosity (m^2/s)
    pub nu_f: f64,
    /// particle diameter (m)
    pub diameter: f64,
    /// fluid density (kg/m^3)
    pub fluid_density: f64,
    /// particle density (kg/m^3)
    pub particle_density: f64,
    /// g cos(alpha) (m/s^2)
    pub gravity_normal: f64,
    /// friction velocity of the forcing, [`friction_velocity`] (m/s)
    pub friction_velocity: f64,
}

/// k and omega of a two-equation closure with the per-cell inputs of their terms: the
/// drag per unit particle volume (Cheng et al. eq 23), filled by the solver, and dphi/dz.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct KOmegaRun {
    /// k and omega
    pub col: KOmegaColumn,
    /// beta of Cheng et al. eq 23 per cell (kg m^-3 s^-1), drag per unit particle volume
    /// per unit slip; it enters the terms multiplied by phi only
    pub drag: Vec<f64>,
    dphidz: Vec<f64>,
}

impl KOmegaRun {
    /// The closure's initial state ([`TwoEquation::initial_state_at`]) in each cell of
    /// volume fraction `phi` of a column of height `height`, particles of `diameter`.
    pub fn new(model: &dyn TwoEquation, phi: &[f64], u_star: f64, height: f64, nu_f: f64, diameter: f64) -> Self {
        let n = phi.len();
        let mut col = KOmegaColumn::new(n, 0.0, 0.0);
        for ((k, w), &p) in col.k.iter_mut().zip(col.omega.iter_mut()).zip(phi) {
            (*k, *w) = model.initial_state_at(p, u_star, height, nu_f, diameter);
        }
        col.save();
        Self { col, drag: vec![0.0; n], dphidz: vec![0.0; n] }
    }

    /// One backward-Euler step of k and omega (or a BDF2 step given the fields one step
    /// back, [`KOmegaColumn::advance`]) (Cheng et al. eqs 21-35) with the shear rate
    /// `shear` of the velocity `u` (whose wall gradient gives the wall friction velocity of
    /// eq 31 with the viscosity nu_f `ratio0` of the wall cell; nu_t vanishes at a wall),
    /// the volume fraction `phi` and [`KOmegaRun::drag`].
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &mut self,
        model: &dyn TwoEquation,
        op: &ColumnOperator,
        physics: &KOmegaPhysics,
        phi: &[f64],
        u: &[f64],
        shear: &[f64],
        ratio0: f64,
        dt: f64,
        before: Option<Before<'_>>,
    ) -> Result<(), TransportFailure> {
        let n = phi.len();
        let zc = op.grid().centres();
        for i in 0..n {
            let (l, r) = (i.saturating_sub(1), (i + 1).min(n - 1));
            self.dphidz[i] = (phi[r] - phi[l]) / (zc[r] - zc[l]);
        }
        let wall_u_star = (physics.nu_f * ratio0 * op.wall_gradient(u).abs()).sqrt();
        let input = TwoEquationInput {
            col: ColumnView {
                z: zc,
                dz: op.grid().dz(),
                phi,
                dudz: shear,
                diameter: physics.diameter,
                nu_f: physics.nu_f,
                transported: &[],
            },
            drag: &self.drag,
            dphidz: &self.dphidz,
            fluid_density: physics.fluid_density,
            particle_density: physics.particle_density,
            gravity_normal: physics.gravity_normal,
            friction_velocity: physics.friction_velocity,
        };
        let geometry = ColumnGeometry { z: zc, dz: op.grid().dz() };
        self.col.advance(model, &input, geometry, wall_u_star, dt, before)
    }

    /// Largest change of k over the last step relative to its maximum.
    pub fn change(&self) -> f64 {
        let k = &self.col.k;
        let kmax = k.iter().fold(1e-300f64, |a, &b| a.max(b));
        k.iter().zip(self.col.saved_k()).fold(0.0f64, |a, (x, y)| a.max((x - y).abs())) / kmax
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_velocity_of_the_driving() {
        assert!((friction_velocity(9.81 * 0.01, 0.1) - (9.81e-3f64).sqrt()).abs() < 1e-15);
        assert_eq!(friction_velocity(-1.0, 0.1), 0.0);
    }
}
