//! # Eulerian two-fluid solver (Chassagne, Bonamy & Chauchat 2023, section 2.1)
//!
//! One-dimensional (wall-normal z) two-fluid model of a sediment bed sheared by a fluid,
//! solved to steady state.
//!
//! ## Equations
//!
//! Unknowns per cell: solid volume fraction phi (eps = 1 - phi), fluid and particle
//! streamwise velocities u_f, u_p, and the granular temperature T when the granular
//! closure is a kinetic theory.
//!
//! * Sediment mass (eq 2.2) with the wall-normal particle flux of the wall-normal momentum
//!   balances of both phases (eqs 2.5-2.6, inertia neglected, the fluid pressure
//!   eliminated; the zero net volume flux of a column with an impermeable bottom gives
//!   u_z^f = -phi w_p / eps):
//!
//!   d phi/dt + d(phi w_p)/dz = 0,
//!   phi w_p = -(eps/K) [phi (rho_p - rho_f) g cos(alpha) + dp_p/dz] - eps D dphi/dz,
//!
//!   with K of eq 2.10 (the drag closure times the hindrance closure, evaluated with the
//!   full slip |u_f - u_p| including the wall-normal slip w_p / eps, less the drift
//!   velocity: the slip u_f - u_p + u_d of eq 4.3) and D the mean-field diffusivity of the
//!   fluctuation closure times the open fraction (1 - phi/phi_max): the drift velocity of
//!   eqs 4.3-4.4, present only when a fluctuation closure is active. Its sign is chosen so
//!   that the dispersion flux runs down the concentration gradient (Rouse balance
//!   w_s phi = -D dphi/dz). A closure of [`saltus_core::DriftForm::Ito`] replaces
//!   eps D dphi/dz by eps d(D phi)/dz, the diffusion limit of its draws (see
//!   docs/closures/fluctuation.md).
//! * Streamwise momentum of both phases (eqs 2.3-2.4, vertical advection neglected: it
//!   vanishes at steady state):
//!
//!   eps rho_f du_f/dt = d/dz[rho_f eps (nu_eff + nu_t) du_f/dz] + eps (rho_f g sin + G) - beta (u_f - u_p),
//!   phi rho_p du_p/dt = d tau_p/dz + phi (rho_p g sin + G) + beta (u_f - u_p),
//!
//!   beta = phi eps K, nu_eff from the viscosity closure, nu_t from the turbulence closure
//!   (eq 2.7-2.8), G the imposed pressure gradient (felt by both phases).
//! * Particle stress: kinetic closures (eqs 2.12-2.15, 2.19-2.23) give p_p = p_el(phi) +
//!   rho_p F1 T and tau_p = mu_s p_el + rho_p d F2 sqrt(T) du_p/dz; local closures
//!   (mu(I), mu(K)) give tau_p = mu(X) p_p with p_p = p_el(phi) + the dilatancy pressure at
//!   which packing(X) = phi (X = I or K at the local shear rate). Rate-independent parts are
//!   regularised, mu p gamma_dot / sqrt(gamma_dot^2 + r^2), `solver.eulerian.shear_rate_regularisation`.
//! * Granular temperature (kinetic closures only), eq 2.16 with the flux 2.18 and the
//!   dissipation by drag 2.25 (linear) or 3.13 (quadratic), as the closure says:
//!
//!   3/2 rho_p phi dT/dt = rho_p d F2 sqrt(T) (du_p/dz)^2 + d/dz(rho_p d F3 sqrt(T) dT/dz)
//!   \- rho_p/d F4 T^{3/2} - c_J phi eps K T.
//!
//! ## Discretisation
//!
//! Finite volumes on the column grid (uniform or stretched from the wall) with the shared
//! operator of [`crate::column::operator`] (face conductances, wall stencils, shear rates,
//! wall and lid rows), backward Euler with coefficients lagged one step:
//!
//! * momentum: one 2x2 block-tridiagonal solve per step couples the two phases through
//!   the drag implicitly (no splitting error however stiff beta is); the Coulomb part of
//!   tau_p is linearised about the previous shear rate (tangent viscosity, so a static bed
//!   is an implicit, very viscous region);
//! * sediment mass: conservative fluxes at faces, zero at the bottom and top, the settling
//!   flux upwinded, p_p linearised in phi (elastic part by its derivative, kinetic part as
//!   (p_kin/phi) phi): the matrix is an M-matrix, so phi stays >= 0 and the mass is
//!   conserved to round-off; the same mobility eps/K multiplies the weight and the pressure
//!   gradient at a face, so the steady state is the discrete hydrostatic balance
//!   dp_p/dz = -phi (rho_p - rho_f) g cos whatever the drag; the drag's dependence on the
//!   settling slip it sets is linearised by Newton's method (a lagged slip is a period-2
//!   oscillation under a quadratic drag, see `volume_fraction`);
//! * granular temperature: production explicit, conduction and both dissipations implicit,
//!   so T >= 0 under any time step.
//!
//! The time step adapts: it grows while phi changes by less than half of
//! `solver.eulerian.max_phi_change` and fields by less than `solver.eulerian.target_field_change`
//! (50 %) per step, and a step that would
//! make phi negative or reach the maximum packing, or produce a non-finite value, is
//! rejected and retried with 0.3 dt. Below `solver.eulerian.dt_min` the run stops and names the
//! time, the cell and the field. The run is steady when the largest relative rate of
//! change of u_f, u_p, phi and T is below `solver.eulerian.steady_tolerance` (1/s) for
//! `solver.eulerian.steady_steps` consecutive steps.
//!
//! A scene pays only for what its closures need: no temperature equation without kinetic
//! theory, no drift diffusivity without an active fluctuation closure.
//!
//! ## Layout
//!
//! The solver is split along its equations: `solver` (construction, getters), `state`
//! (the solution and the copy a rejection restores), `coefficients` (everything recomputed
//! from the state; one batch call per closure family per evaluation), `workspace` (the
//! storage of the coefficients and the scratch space of the solves), `stress` (particle pressure and shear stress), `momentum`, `temperature`,
//! `volume_fraction`, `k_omega` (one implicit step of each equation), `stepper` (the
//! [`crate::run::Stepper`]: one accepted step per call) and `report` (profiles and
//! summary, read without advancing anything). The coefficients always belong to the
//! current state: the stepper evaluates them after every accepted step (and a BDF2 step
//! of the time-accurate stepping once more at the extrapolation of the last two states,
//! about which it linearises).

mod block;
mod coefficients;
mod config;
mod k_omega;
mod momentum;
mod report;
mod rheology;
mod solver;
mod state;
mod stepper;
mod stress;
mod temperature;
mod volume_fraction;
mod warm;
mod workspace;

pub use block::BlockTridiagonal;
pub use config::{Config, Domain, Settings, Top};
pub use report::Derived;
pub use rheology::{Elastic, Rheology};
pub use solver::{Eulerian, PHI_FLOOR};
pub use warm::checkpoint_refusal;

/// The stages of a step whose wall time the solver counts: the coefficients of the state
/// (closures, drag, stresses), the streamwise momentum of both phases, the granular
/// temperature (kinetic) or the local pressure, k and omega, the volume fraction.
pub const STAGES: [&str; 5] = ["coefficients", "momentum", "granular", "turbulence", "volume_fraction"];

/// Indices into [`STAGES`].
mod stage {
    pub(super) const COEFFICIENTS: usize = 0;
    pub(super) const MOMENTUM: usize = 1;
    pub(super) const GRANULAR: usize = 2;
    pub(super) const TURBULENCE: usize = 3;
    pub(super) const VOLUME_FRACTION: usize = 4;
}
