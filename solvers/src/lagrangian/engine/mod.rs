//! The dry DEM: particles, contact laws, flat walls, half-cylinders, the neighbour list,
//! the pair loop and the leapfrog step, with the fixed chunking that keeps every sum
//! independent of the thread count, and the contact sums a sampled step takes for the
//! granular fields. Nothing here knows of the fluid: the fluid force comes in as an
//! external force per particle. Uses nothing else of the Lagrangian solver.

pub mod chunks;
pub mod contact;
pub mod contact_sums;
pub mod cylinders;
pub mod dem;
pub mod neighbours;
mod pairs;
pub mod particles;
mod scratch;
pub mod slicing;
pub mod walls;
