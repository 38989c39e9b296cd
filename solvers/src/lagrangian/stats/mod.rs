//! What a run measures over time: the time-averaged profiles, the block errors of the
//! transport rate, the steady-state test, the granular temperature history against Haff's
//! law and the granular fields (stresses, fluxes, dissipation, I, J, mu, coordination).
//! Uses [`super::engine`] and [`super::coupling`].

pub mod blocking;
pub mod cooling;
pub mod granular;
pub mod statistics;
pub mod steady;
pub mod truncation;
