//! The state of a Lagrangian run: everything the steps to come read, and nothing else. A
//! checkpoint is this struct's own serialisation ([`crate::lagrangian::output::checkpoint`]),
//! so that a field added here is carried by restarts without a second list.
//!
//! The neighbour list is part of the DEM's state rather than rebuilt: a rebuild at another
//! step would wrap the positions and order the pairs differently, and the sums would
//! round differently.

use serde::{Deserialize, Serialize};

use crate::column::FluidColumn;
use crate::lagrangian::coupling::averaging::CellSums;
use crate::lagrangian::coupling::damping::SlipAverage;
use crate::lagrangian::coupling::drag::{FluidField, FluidForces};
use crate::lagrangian::engine::dem::Dem;
use crate::lagrangian::stats::granular::GranularStats;
use crate::lagrangian::stats::statistics::Stats;
use crate::lagrangian::stats::steady::Steady;
use crate::lagrangian::stats::truncation::Truncation;

/// What the run is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) enum Stage {
    /// settling the bed under gravity, fluid at rest
    Deposition,
    /// the flow
    Flow,
}

/// The state a checkpoint carries.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct State {
    pub(crate) stage: Stage,
    /// time of the flow (after the deposition) (s)
    pub(crate) time: f64,
    /// DEM steps of the flow
    pub(crate) steps: u64,
    /// DEM steps of the deposition taken
    pub(crate) settle_steps: u64,
    /// particles, neighbour list with its springs, wall histories, body force
    pub(crate) dem: Dem,
    /// every particle's random stream, fluctuation draw and clock, and the slip and drag
    /// coefficient of the last evaluation
    pub(crate) forces: FluidForces,
    /// the fluid field the particles see
    pub(crate) field: FluidField,
    /// the fluid column (velocity, relaxed eddy viscosity, k and omega), when coupled
    pub(crate) column: Option<FluidColumn>,
    /// the particle sums of the last fluid update
    pub(crate) sums: CellSums,
    /// the averages of the last fluid update: volume fraction, particle velocity, drag
    /// coefficient, Reynolds stress per cell
    pub(crate) phi: Vec<f64>,
    pub(crate) u_p: Vec<f64>,
    pub(crate) beta: Vec<f64>,
    pub(crate) tau_t: Vec<f64>,
    /// time averages of the profiles and of the transport rate
    pub(crate) stats: Stats,
    /// the granular fields' sums, when the scene asks for them
    pub(crate) granular: Option<GranularStats>,
    /// the steady-state detector
    pub(crate) steady: Steady,
    /// the transport rate of every fluid update in batches, for the averaging window and
    /// the stopping rule on a requested error; saved after the state
    /// ([`crate::lagrangian::output::checkpoint`]), so that a checkpoint written before it
    /// was kept still reads
    #[serde(skip)]
    pub(crate) truncation: Truncation,
    /// slice volume A dz (m^3) of the column as fitted to the deposit
    pub(crate) cell_volume: f64,
    /// nominal bed surface above the column bottom (m), measured after the deposition
    pub(crate) bed_surface: f64,
    /// time averages of the cell-mean relative velocity for the drag damping of a
    /// two-equation closure (Cheng et al. eq 24); no cell when the closure does not ask
    pub(crate) slip: SlipAverage,
}

impl State {
    /// Time of the current phase (s): of the deposition, then of the flow.
    pub(crate) fn phase_time(&self) -> f64 {
        match self.stage {
            Stage::Deposition => self.settle_steps as f64 * self.dem.dt(),
            Stage::Flow => self.time,
        }
    }

    /// Whether the sizes of this state fit together (a decoded checkpoint that does not
    /// is refused, never indexed).
    pub(crate) fn fits(&self) -> bool {
        let p = self.dem.particles();
        let n = p.len();
        let cells = self.field.u.len();
        let particle_arrays = [&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz, &p.radius, &p.inv_mass];
        let cell_arrays =
            [&self.field.phi, &self.field.nu_t, &self.field.reynolds, &self.field.re_ratio, &self.sums.vol];
        p.n_mobile <= n
            && particle_arrays.iter().all(|a| a.len() == n)
            && p.inv_inertia.len() == n
            && self.forces.fluctuations().len() == n
            && self.forces.eddy_clocks().len() == n
            && cells > 0
            && cell_arrays.iter().all(|a| a.len() == cells)
            && [&self.phi, &self.u_p, &self.beta, &self.tau_t].iter().all(|a| a.len() == cells)
            && self.column.as_ref().is_none_or(|c| c.velocity().len() == cells)
            && self.granular.as_ref().is_none_or(|g| g.fits(cells))
            && (self.slip.is_empty() || self.slip.len() == cells)
    }
}
