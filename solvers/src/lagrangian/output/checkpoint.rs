//! The state of a Lagrangian run as a checkpoint ([`crate::run::checkpoint`]): the
//! solver's [`State`] in bincode (every f64 as its 8 bytes), so that a restart goes on bit
//! for bit and a field added to the state is carried without a second list.
//!
//! Not saved: what the scene gives (closures, time step, fluid period, thread pool: the
//! restart sets the solver up from the same scene first, [`crate::lagrangian::run::params`])
//! and the workspace that every step refills.

use bincode::Options as _;

use crate::lagrangian::run::state::State;

fn options() -> impl bincode::Options {
    bincode::DefaultOptions::new()
}

/// Append `state` to `out`, then its batched transport rate (the averaging window's
/// series), which a checkpoint of an earlier program lacks.
pub(crate) fn save(state: &State, out: &mut Vec<u8>) -> Result<(), String> {
    options().serialize_into(&mut *out, state).map_err(|e| format!("cannot encode the DEM state: {e}"))?;
    options().serialize_into(out, &state.truncation).map_err(|e| format!("cannot encode the DEM state: {e}"))
}

/// The state `save` wrote, after checking that its sizes fit together: a state that does
/// not is refused, never indexed.
pub(crate) fn decode(bytes: &[u8]) -> Result<State, String> {
    let mut rest = bytes;
    let mut s: State = options()
        .with_limit(bytes.len() as u64)
        .deserialize_from(&mut rest)
        .map_err(|e| format!("cannot decode the DEM state: {e}"))?;
    // without the series (a checkpoint written before it was kept) the window starts afresh
    if !rest.is_empty() {
        s.truncation = options()
            .with_limit(rest.len() as u64)
            .deserialize(rest)
            .map_err(|e| format!("cannot decode the DEM state's transport-rate series: {e}"))?;
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
