//! The column's side of the two-way coupling, once per fluid period: the column advanced
//! by one period under the grains' averages of the period just ended (phi, beta, u_p and,
//! for a two-equation closure, the time-averaged slip of Cheng et al. 2018 eq 24), then
//! the fluid field the grains see refreshed from it (velocity, eddy viscosity, k and
//! omega, Reynolds stress, flow scales).

use std::borrow::Cow;

use saltus_core::{DragLaw, Hindrance};

use super::averaging::CellSums;
use super::damping::{DampingLaw, SlipAverage};
use super::drag::FluidField;
use crate::column::{Closures, Coupling, FluidColumn};
use crate::inputs;
use crate::run::{Breakdown, Place};

/// Particle or fluid speed beyond which the run is declared unstable (m/s): far above
/// any bedload or settling velocity, reached only when the time step is too large for
/// the stiffness or the fluid period too long for the coupling.
pub const MAX_SPEED: f64 = 100.0;

/// The closures and constants of the exchange.
pub(crate) struct ExchangeModels<'a> {
    /// the column's closures (viscosity, turbulence, side walls)
    pub closures: Closures<'a>,
    /// the drag law and hindrance of eq 24's damping coefficient
    pub drag: &'a dyn DragLaw,
    pub hindrance: &'a dyn Hindrance,
    /// fluid density (kg/m^3)
    pub rho_f: f64,
}

/// The grains as the fluid sees them over the period just ended.
pub(crate) struct Grains<'a> {
    /// the particle sums of the period's last averaging
    pub sums: &'a CellSums,
    /// drag coefficient beta per cell (kg m^-3 s^-1)
    pub beta: &'a [f64],
    /// particle velocity per cell (m/s)
    pub u_p: &'a [f64],
    /// bed surface of the flow scales (m)
    pub bed_surface: f64,
}

/// Advance `col` by one fluid period `tau_f` from flow time `time` under the `grains`'
/// averages and the fluid volume fraction of `field`, with the pressure gradient
/// `forced` (Pa/m) of a time-dependent forcing at the period's end, then refresh `field`
/// and the Reynolds stress `tau_t` on the column's faces from it. `slip` takes the
/// period's relative velocity for eq 24 when the turbulence closure asks for it. A
/// column that fails or runs away is a breakdown at `time`, named with its cause.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_column(
    col: &mut FluidColumn,
    models: &ExchangeModels<'_>,
    grains: &Grains<'_>,
    field: &mut FluidField,
    slip: &mut SlipAverage,
    tau_t: &mut [f64],
    (time, tau_f): (f64, f64),
    forced: Option<f64>,
) -> Result<(), Breakdown> {
    if let Some(start) = models.closures.turbulence.as_two_equation().and_then(|m| m.slip_average_start()) {
        let law = DampingLaw {
            drag: models.drag,
            hindrance: models.hindrance,
            diameter: col.params().diameter,
            rho_f: models.rho_f,
            nu_f: col.params().viscosity,
        };
        slip.update(time, start, grains.sums, col.velocity(), &field.phi, &law);
        col.set_damping_drag(&slip.beta);
    }
    if let Some(g) = forced {
        col.set_pressure_gradient(g).map_err(|e| Breakdown {
            time,
            place: Place::Column,
            field: Cow::Borrowed("pressure_gradient"),
            value: g,
            reason: e.to_string(),
        })?;
    }
    let coupling = Coupling { phi: &field.phi, beta: grains.beta, u_p: grains.u_p };
    if let Err(e) = col.step(tau_f, &coupling, &models.closures) {
        return Err(Breakdown {
            time,
            place: Place::Column,
            field: Cow::Borrowed("u_f"),
            value: f64::NAN,
            reason: e.to_string(),
        });
    }
    // a runaway column (a fluid period far beyond the particles' response time leaves
    // the drag no hold on it) is stopped here with its cause, before the particles it
    // would fling blow up
    if let Some((c, &u)) = col.velocity().iter().enumerate().find(|(_, u)| u.is_nan() || u.abs() > MAX_SPEED) {
        return Err(Breakdown {
            time,
            place: Place::Cell { index: c, z: col.grid().centres()[c] },
            field: Cow::Borrowed("u_f"),
            value: u,
            reason: format!(
                "fluid velocity above {MAX_SPEED} m/s: the driving is too strong or solver.lagrangian.fluid_period = {} s too long for the coupling",
                saltus_core::param::number(tau_f)
            ),
        });
    }
    field.set_velocity(col.velocity());
    field.nu_t.copy_from_slice(col.eddy_viscosity());
    if let Some((k, omega)) = col.k_omega() {
        let [kf, wf] = &mut field.k_omega;
        kf.clear();
        kf.extend_from_slice(k);
        wf.clear();
        wf.extend_from_slice(omega);
    }
    for ((r, &nu), &g) in field.reynolds.iter_mut().zip(col.eddy_viscosity()).zip(col.shear_rate()) {
        *r = inputs::reynolds_stress(nu, g);
    }
    col.reynolds_stress(tau_t);
    let grid = col.grid();
    let bed = inputs::bed_surface(grid.centres(), &field.phi, grains.bed_surface);
    field.scales = inputs::flow_scales(grid.centres(), grid.dz(), col.velocity(), grid.height(), bed);
    Ok(())
}
