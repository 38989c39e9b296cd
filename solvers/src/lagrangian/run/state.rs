//! The state of a Lagrangian run: everything the steps to come read, and nothing else. A
//! checkpoint ([`crate::run::checkpoint`]) is this struct's own serialisation (`save` and
//! `decode` below: bincode, every f64 as its 8 bytes), so that a restart goes on bit for
//! bit and a field added here is carried by restarts without a second list.
//!
//! Not saved: what the scene gives (closures, time step, fluid period, thread pool: the
//! restart sets the solver up from the same scene first, [`crate::lagrangian::run::params`])
//! and the workspace that every step refills.
//!
//! The neighbour list is part of the DEM's state rather than rebuilt: a rebuild at another
//! step would wrap the positions and order the pairs differently, and the sums would
//! round differently.

use bincode::Options as _;
use serde::{Deserialize, Serialize};

use crate::column::FluidColumn;
use crate::lagrangian::coupling::averaging::CellSums;
use crate::lagrangian::coupling::damping::SlipAverage;
use crate::lagrangian::coupling::drag::{FluidField, FluidForces};
use crate::lagrangian::coupling::smoothing::PhiWindow;
use crate::lagrangian::engine::contact_sums::Slices;
use crate::lagrangian::engine::dem::Dem;
use crate::lagrangian::stats::granular::GranularStats;
use crate::lagrangian::stats::statistics::Stats;
use crate::lagrangian::stats::steady::Steady;
use crate::lagrangian::stats::truncation::Truncation;
use crate::run::start_profiles::StartProfiles;

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
    /// the stopping rule on a requested error; saved after the state (`save`), so that a
    /// checkpoint written before it was kept still reads
    #[serde(skip)]
    pub(crate) truncation: Truncation,
    /// slice volume A dz (m^3) of the column as fitted to the deposit
    pub(crate) cell_volume: f64,
    /// nominal bed surface above the column bottom (m), measured after the deposition
    pub(crate) bed_surface: f64,
    /// time averages of the cell-mean relative velocity for the drag damping of a
    /// two-equation closure (Cheng et al. eq 24); no cell when the closure does not ask
    pub(crate) slip: SlipAverage,
    /// the profiles whose velocities the flow starts with at the end of the deposition
    /// (`saltus run --warm-start` from a two-fluid run), until it starts; saved after the
    /// series (`save`), so that a checkpoint written without it still reads
    #[serde(skip)]
    pub(crate) start: Option<StartProfiles>,
    /// the slice volumes summed over the DEM steps since the last fluid update, for the
    /// time-mean volume fraction of Cheng et al. eq 14 (`phi_average = "fluid_period"`;
    /// empty otherwise); saved after the transport-rate series (`save`), so that a
    /// checkpoint written before it was kept still reads
    #[serde(skip)]
    pub(crate) phi_window: PhiWindow,
}

impl State {
    /// The averaging slices (the fluid cells) in particle coordinates.
    pub(crate) fn slices(&self) -> Slices {
        Slices { base: self.field.base, dz: self.field.dz, n: self.field.u.len() }
    }

    /// Time of the current phase (s): of the deposition, then of the flow.
    pub(crate) fn phase_time(&self) -> f64 {
        match self.stage {
            Stage::Deposition => self.settle_steps as f64 * self.dem.dt(),
            Stage::Flow => self.time,
        }
    }

    /// The instantaneous transport rate per unit width (m^2/s): the slices' sum of V_p v_x
    /// over the bed area, from the last averaging.
    pub(crate) fn transport_rate(&self) -> f64 {
        self.sums.v[0].iter().sum::<f64>() / (self.cell_volume / self.field.dz)
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
            && (self.phi_window.vol.is_empty() || self.phi_window.vol.len() == cells)
    }
}

fn options() -> impl bincode::Options {
    bincode::DefaultOptions::new()
}

/// Append `state` to `out`, then its batched transport rate (the averaging window's
/// series), the profiles the flow is to start from, eq 14's window and the series' prior
/// statistical inefficiency, which a checkpoint of an earlier program lacks.
pub(crate) fn save(state: &State, out: &mut Vec<u8>) -> Result<(), String> {
    let fail = |e: bincode::Error| format!("cannot encode the DEM state: {e}");
    options().serialize_into(&mut *out, state).map_err(fail)?;
    options().serialize_into(&mut *out, &state.truncation).map_err(fail)?;
    options().serialize_into(&mut *out, &state.start).map_err(fail)?;
    // a scene without eq 14's time mean writes an empty window
    options().serialize_into(&mut *out, &state.phi_window).map_err(fail)?;
    options().serialize_into(out, &state.truncation.prior()).map_err(fail)
}

/// The next part `save` appended after the state, `None` where the bytes end.
fn segment<T: serde::de::DeserializeOwned>(rest: &mut &[u8], what: &str) -> Result<Option<T>, String> {
    if rest.is_empty() {
        return Ok(None);
    }
    options()
        .with_limit(rest.len() as u64)
        .deserialize_from(rest)
        .map(Some)
        .map_err(|e| format!("cannot decode the DEM state's {what}: {e}"))
}

/// The state `save` wrote, after checking that its sizes fit together: a state that does
/// not is refused, never indexed.
pub(crate) fn decode(bytes: &[u8]) -> Result<State, String> {
    let mut rest = bytes;
    let mut s: State = options()
        .with_limit(bytes.len() as u64)
        .deserialize_from(&mut rest)
        .map_err(|e| format!("cannot decode the DEM state: {e}"))?;
    // each later part is absent from a checkpoint written before it was kept: the series
    // then starts afresh, no profiles wait, no window of eq 14 is open
    if let Some(t) = segment(&mut rest, "transport-rate series")? {
        s.truncation = t;
    }
    if let Some(p) = segment(&mut rest, "starting profiles")? {
        s.start = p;
    }
    if let Some(w) = segment(&mut rest, "volume-fraction window")? {
        s.phi_window = w;
    }
    if let Some(prior) = segment(&mut rest, "prior statistical inefficiency")? {
        s.truncation.set_prior(prior);
    }
    if !s.fits() {
        return Err(format!(
            "the DEM state's arrays do not fit together ({} particles, {} fluid cells)",
            s.dem.particles().len(),
            s.field.u.len()
        ));
    }
    Ok(s)
}

/// The state `save` wrote ([`decode`]), after checking that it was written with the time
/// step `dt` and the same column (`coupled`) and granular fields (`granular`) as this
/// scene's, for a restart that goes on with it as it is.
pub(crate) fn load(bytes: &[u8], dt: f64, coupled: bool, granular: bool) -> Result<State, String> {
    let s = decode(bytes)?;
    if !(s.column.is_some() == coupled && s.granular.is_some() == granular && s.dem.dt() == dt) {
        return Err(format!(
            "the DEM state does not fit this scene ({} particles, {} fluid cells, time step {:e} s)",
            s.dem.particles().len(),
            s.field.u.len(),
            s.dem.dt()
        ));
    }
    Ok(s)
}
