//! Parameters, closures, coupling inputs and steady report of a [`super::FluidColumn`].

use saltus_core::{EffectiveViscosity, Turbulence, WallFriction};

use super::side_walls::SideWalls;
use super::ColumnError;

/// Boundary condition at the top of the column (z = H).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum TopBoundary {
    /// free surface: zero shear stress, du/dz = 0
    FreeSurface,
    /// moving lid (Couette): u = `velocity` (m/s) at z = H
    Lid {
        /// lid velocity (m/s)
        velocity: f64,
    },
    /// symmetry plane (channel centreline): zero shear stress; for this equation the same
    /// discrete condition as [`TopBoundary::FreeSurface`], kept distinct for clarity
    Symmetry,
}

/// Physical and numerical parameters of a [`super::FluidColumn`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ColumnParams {
    /// fluid density rho_f (kg/m^3)
    pub density: f64,
    /// clear-fluid kinematic viscosity nu_f (m^2/s)
    pub viscosity: f64,
    /// particle diameter d (m), handed to the turbulence closure (0 for clear water)
    pub diameter: f64,
    /// streamwise gravity g sin(alpha) (m/s^2)
    pub gravity_x: f64,
    /// imposed streamwise pressure gradient G_x = -dp/dx (Pa/m)
    pub pressure_gradient: f64,
    /// top boundary condition
    pub top: TopBoundary,
    /// particle density rho_p (kg/m^3), for the two-phase terms of a two-equation
    /// closure (buoyancy, drag damping; Cheng et al. eqs 21, 25)
    pub particle_density: f64,
    /// wall-normal gravity g cos(alpha) (m/s^2), for the buoyancy term of a two-equation
    /// closure (Cheng et al. eq 21)
    pub gravity_normal: f64,
    /// friction velocity of the forcing at the bed surface (m/s) for the rough-wall and
    /// in-bed omega of a two-equation closure (Cheng et al. eq 34); `None`: that of the
    /// driving over the whole column, sqrt((g sin(alpha) + G_x / rho_f) H)
    pub friction_velocity: Option<f64>,
    /// under-relaxation omega in (0, 1] of nu_t in [`super::FluidColumn::step`] (after the first
    /// step) and [`super::FluidColumn::solve_steady`]: nu_t <- omega nu_t(u) + (1 - omega) nu_t. The default 0.5 turns the Picard map of a
    /// fully turbulent mixing-length layer (nu_t <- C / nu_t, which oscillates with
    /// omega = 1) into a Newton (Babylonian) iteration.
    pub relaxation: f64,
    /// two smooth lateral walls of a quasi-2D channel (Maurin et al. 2015 section III B;
    /// [`super::side_walls`]), whose friction the fluid loses with the friction factor of
    /// [`Closures::wall_friction`]; `None`: no walls
    #[serde(default)]
    pub side_walls: Option<SideWalls>,
}

impl Default for ColumnParams {
    /// Water (rho_f = 1000, nu_f = 1e-6), no particle, no driving, free surface, omega = 0.5.
    fn default() -> Self {
        Self {
            density: 1000.0,
            viscosity: 1.0e-6,
            diameter: 0.0,
            gravity_x: 0.0,
            pressure_gradient: 0.0,
            top: TopBoundary::FreeSurface,
            particle_density: 2650.0,
            gravity_normal: 9.81,
            friction_velocity: None,
            relaxation: 0.5,
            side_walls: None,
        }
    }
}

/// The closures the column uses.
#[derive(Clone, Copy, Debug)]
pub struct Closures<'a> {
    /// effective viscosity nu_eff = nu_f ratio(phi)
    pub viscosity: &'a dyn EffectiveViscosity,
    /// eddy viscosity nu_t: an algebraic closure, or a two-equation one (k-omega) whose k
    /// and omega the column then allocates (first step) and advances
    pub turbulence: &'a dyn Turbulence,
    /// friction factor of the side walls ([`ColumnParams::side_walls`]); `None`: the fluid
    /// does not feel the walls
    pub wall_friction: Option<&'a dyn WallFriction>,
}

/// Per-cell coupling with the particle phase, supplied by the caller every step (all
/// zero for clear water).
#[derive(Clone, Copy, Debug)]
pub struct Coupling<'a> {
    /// solid volume fraction phi per cell, in [0, 1)
    pub phi: &'a [f64],
    /// implicit drag coefficient beta per cell (kg m^-3 s^-1), >= 0: the drag on the fluid
    /// per unit mixture volume is -beta (u_f - u_p)
    pub beta: &'a [f64],
    /// particle velocity u_p per cell (m/s)
    pub u_p: &'a [f64],
}

/// Outcome of [`super::FluidColumn::solve_steady`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteadyReport {
    /// linear solves performed
    pub iterations: usize,
    /// final relative residual of the steady equation (see [`super::FluidColumn::residual`])
    pub residual: f64,
}

impl ColumnParams {
    /// Refuse non-finite or out-of-range parameters, naming the parameter.
    pub fn validate(&self) -> Result<(), ColumnError> {
        let p = self;
        let positive = |name, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ColumnError::InvalidParameter { name, value: v, reason: "must be finite and > 0" })
            }
        };
        positive("fluid density", p.density)?;
        positive("fluid viscosity", p.viscosity)?;
        if !(p.diameter.is_finite() && p.diameter >= 0.0) {
            return Err(ColumnError::InvalidParameter {
                name: "diameter",
                value: p.diameter,
                reason: "must be finite and >= 0",
            });
        }
        positive("particle density", p.particle_density)?;
        if let Some(u) = p.friction_velocity {
            if !(u.is_finite() && u >= 0.0) {
                return Err(ColumnError::InvalidParameter {
                    name: "friction_velocity",
                    value: u,
                    reason: "must be finite and >= 0",
                });
            }
        }
        for (name, v) in [
            ("gravity_x", p.gravity_x),
            ("pressure_gradient", p.pressure_gradient),
            ("gravity_normal", p.gravity_normal),
        ] {
            if !v.is_finite() {
                return Err(ColumnError::InvalidParameter { name, value: v, reason: "must be finite" });
            }
        }
        if let TopBoundary::Lid { velocity } = p.top {
            if !velocity.is_finite() {
                return Err(ColumnError::InvalidParameter {
                    name: "lid velocity",
                    value: velocity,
                    reason: "must be finite",
                });
            }
        }
        if let Some(w) = p.side_walls {
            positive("side-wall width", w.width)?;
        }
        if !(p.relaxation > 0.0 && p.relaxation <= 1.0) {
            return Err(ColumnError::InvalidParameter {
                name: "relaxation",
                value: p.relaxation,
                reason: "must be in (0, 1]",
            });
        }
        Ok(())
    }
}
