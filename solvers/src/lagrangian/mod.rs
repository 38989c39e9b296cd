//! # Lagrangian solver: soft-sphere DEM coupled to the 1D fluid column (Maurin et al. 2015)

pub mod contact;
pub mod dem;
pub mod neighbours;
pub mod particles;

pub use contact::{ContactLaw, ContactModel};
pub use dem::{Dem, Wall};
pub use neighbours::NeighbourList;
pub use particles::{Box3, Particles};
