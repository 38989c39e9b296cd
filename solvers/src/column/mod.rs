//! Shared 1D column fluid discretisation.
//!
//! The discrete operator ([`operator::ColumnOperator`]: grid metrics, wall stencils, face
//! conductances, face values, shear rate, wall and lid rows) and the turbulence of the
//! column ([`turbulence`]: the friction velocity, the eddy viscosity with its one
//! relaxation policy, the k-omega inputs and step) exist once. The Lagrangian DEM solver
//! advances the streamwise fluid velocity u_f(z, t) with [`FluidColumn`] (operator +
//! turbulence, a scalar tridiagonal system); the Eulerian two-fluid solver assembles the
//! same operator into each phase of its 2x2 block system through [`Band`].
//!
//! # Equation
//!
//! Chassagne et al. 2023 eq 2.3 (without the vertical advection, zero in a uniform 1D
//! column) with the fluid stress of eq 2.7, equivalently Maurin et al. 2015 eq 19 with an
//! imposed pressure gradient:
//!
//! ```text
//! eps rho_f du/dt = d/dz[ rho_f eps (nu_eff(phi) + nu_t) du/dz ]
//!                   + eps rho_f g sin(alpha) + eps G_x - beta (u - u_p) - gamma_w u
//! ```
//!
//! with eps = 1 - phi, nu_eff = nu_f ratio(phi) ([`saltus_core::EffectiveViscosity`]),
//! nu_t = l_m^2 |du/dz| from [`saltus_core::Turbulence::eddy_viscosity`] (Chassagne eq
//! 2.8) or nu_t = alpha* k / omega of a two-equation closure (Cheng et al. eq 29, k and
//! omega advanced by [`k_omega::KOmegaColumn`] after each momentum step), G_x = -dp/dx (Pa/m) and beta (kg m^-3 s^-1) the implicit drag coefficient with
//! the particle velocity u_p, both per cell from the caller ([`Coupling`]). gamma_w u is
//! the friction of two smooth side walls of a quasi-2D channel (Maurin et al. 2015
//! section III B, [`side_walls`]; [`ColumnParams::side_walls`], absent by default):
//! gamma_w = eps rho_f f_w |u| / (4 W) with the smooth-wall friction factor f_w, lagged
//! like nu_t and implicit in u like the drag.
//!
//! eps factors: eps multiplies both nu_eff and nu_t, once, as in Chassagne eq 2.7. Maurin
//! eq 19 writes eps nu_e + nu_t with nu_t = eps l_m^2 |du/dz| (its eq 4): the same
//! product, so the turbulence closures return nu_t without eps and the solver applies it.
//! The driving (gravity along the slope and the imposed pressure gradient) acts on the
//! fluid fraction only, hence eps on both; the drag is per unit mixture volume (no eps).
//!
//! # Discretisation
//!
//! Cell-centred finite volumes on a [`Grid`] (faces z_f[0..=n], centres z_c, widths dz;
//! uniform or stretched). Per cell i the balance integrated over the cell is
//! tau_{i+1/2} - tau_{i-1/2} + (S_i - beta_i (u_i - u_p,i)) dz_i = eps_i rho_f dz_i du_i/dt.
//!
//! * Interior face flux tau_{j} = rho_f (u_j - u_{j-1}) / (d_L / k_{j-1} + d_R / k_j) with
//!   k = eps (nu_eff + nu_t) per cell and d_L, d_R the distances from the face to the two
//!   centres: the distance-weighted harmonic mean of the cell diffusivities (series
//!   resistance). It gives the exact flux of a piecewise-linear profile across a jump of
//!   k (the bed interface, where eps nu jumps by orders of magnitude), where the arithmetic
//!   mean lets the large side leak through the small one. For uniform k it is the usual
//!   second-order central difference.
//! * Wall fluxes (ghost-free): the wall gradient is the second-order one-sided
//!   derivative of the quadratic through the wall value and the first two centres
//!   (uniform grid: du/dz(0) = (9 u_0 - u_1 - 8 u_w) / (3 dz)), times rho_f k of the wall
//!   cell. The plain half-cell difference (u_0 - u_w)/(dz/2) is only first-order at the
//!   wall and shifts the laminar open-channel profile by G dz^2 / (8 mu); with the
//!   quadratic one the scheme is exact at the cell centres for the quadratic laminar
//!   solution (docs/verification.md, benchmark 1) as well as for the linear Couette one. The
//!   stencil stays in the tridiagonal band and keeps the M-matrix sign pattern.
//! * Face velocities: flux-continuity interpolation (w_L u_L + w_R u_R)/(w_L + w_R),
//!   w = k / distance, consistent with the harmonic face diffusivity (linear
//!   interpolation for uniform k); top free surface: zero-slope quadratic through the
//!   last two centres. The shear rate handed to the turbulence closure is the
//!   difference over each cell of the linearly interpolated face values (central
//!   difference on a uniform grid), independent of the diffusivity; under a zero-stress
//!   top its top value is the last centre's
//!   ([`operator::ColumnOperator::stress_free_shear_top`]).
//! * Eddy viscosity: evaluated from the velocity at the start of each step and relaxed,
//!   nu_t <- w nu_t(u) + (1 - w) nu_t with w = [`ColumnParams::relaxation`] (the first
//!   evaluation unrelaxed), the one policy of both solvers
//!   ([`turbulence::EddyViscosity`]).
//!
//! # Boundary conditions
//!
//! Bottom: no-slip wall u = 0 at z = 0. Top ([`TopBoundary`]): `FreeSurface` and
//! `Symmetry` (zero stress), `Lid { velocity }` (u = U at z = H, same one-sided quadratic
//! gradient as the bottom wall).
//!
//! # Time stepping and steady state
//!
//! Backward Euler, diffusion and drag fully implicit, nu_t lagged and relaxed (Picard), solved by
//! the tridiagonal double sweep (Thomas) as in Maurin et al. 2015 (text after eq 19):
//! [`FluidColumn::step`] (with a two-equation closure, k and omega then take one
//! backward-Euler step with the shear of the new velocity). [`FluidColumn::solve_steady`]
//! iterates Picard with infinite pseudo time step and under-relaxed nu_t until the
//! residual of the steady equation is below a tolerance (with a two-equation closure: a
//! steady momentum solve, then a pseudo-time step of k and omega, until both settle).
//! Inputs are checked (a NaN in beta is an error naming the cell and
//! the field) and a non-finite u_f after a solve is an error naming the time, the cell and
//! the field, never a panic.

pub mod bdf2;
mod fluid;
mod grid;
pub mod k_omega;
pub mod operator;
mod params;
pub mod side_walls;
pub mod tridiagonal;
pub mod turbulence;

pub use fluid::FluidColumn;
pub use grid::Grid;
pub use operator::{Band, ColumnOperator};
pub use params::{Closures, ColumnParams, Coupling, SteadyReport, TopBoundary};
pub use side_walls::SideWalls;
pub use tridiagonal::Tridiagonal;

/// Errors of the column solver.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ColumnError {
    /// A parameter of the grid or the column is out of range.
    #[error("column: {name} = {value}: {reason}")]
    InvalidParameter {
        /// parameter name
        name: &'static str,
        /// value given
        value: f64,
        /// allowed values
        reason: &'static str,
    },
    /// An input slice does not have one value per cell.
    #[error("column: input `{field}` has {found} values, the grid has {expected} cells")]
    Length {
        /// field name
        field: &'static str,
        /// number of cells
        expected: usize,
        /// length given
        found: usize,
    },
    /// An input value is not finite or out of range.
    #[error("column: input `{field}` = {value} at cell {cell} (z = {z} m): {reason}")]
    InvalidInput {
        /// field name (`phi`, `beta`, `u_p`, `u_f`)
        field: &'static str,
        /// cell index from the bottom
        cell: usize,
        /// cell centre (m)
        z: f64,
        /// value given
        value: f64,
        /// allowed values
        reason: &'static str,
    },
    /// A computed field became NaN or infinite.
    #[error("column: non-finite {field} at cell {cell} (z = {z} m) at t = {time} s")]
    NonFinite {
        /// field name (`u_f`, `nu_t`)
        field: &'static str,
        /// cell index from the bottom
        cell: usize,
        /// cell centre (m)
        z: f64,
        /// simulated time (s)
        time: f64,
    },
    /// Zero or non-finite pivot in the tridiagonal solve.
    #[error("column: zero or non-finite pivot at row {row} of the momentum system at t = {time} s")]
    Singular {
        /// row (cell) index
        row: usize,
        /// simulated time (s)
        time: f64,
    },
    /// The steady solve did not reach the tolerance.
    #[error("column: steady solve not converged after {iterations} iterations: residual {residual:e} > tol {tol:e}")]
    NotConverged {
        /// linear solves performed
        iterations: usize,
        /// last relative residual
        residual: f64,
        /// tolerance asked
        tol: f64,
    },
    /// A turbulence closure that transports fields other than the k and omega of a
    /// two-equation closure.
    #[error("column: turbulence model `{model}` transports fields other than the k and omega of a two-equation closure, which the column solver does not advance")]
    Unsupported {
        /// model name
        model: &'static str,
    },
    /// k or omega of a two-equation closure not finite, negative or singular after a step.
    #[error("column: {field} = {value} at cell {cell} (z = {z} m) at t = {time} s: {reason}")]
    TwoEquation {
        /// `k` or `omega`
        field: &'static str,
        /// cell index from the bottom
        cell: usize,
        /// cell centre (m)
        z: f64,
        /// the offending value
        value: f64,
        /// what is wrong
        reason: &'static str,
        /// simulated time (s)
        time: f64,
    },
}

impl From<ColumnError> for saltus_core::Error {
    fn from(e: ColumnError) -> Self {
        saltus_core::Error::Invalid(e.to_string())
    }
}
