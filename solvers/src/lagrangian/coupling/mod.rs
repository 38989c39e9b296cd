//! The fluid as the grains see it and the grains as the fluid sees them: the fluid field
//! and the drag (with the fluctuation closures) on each particle, the averages of the
//! particles on the cells and the momentum exchange with the column. Uses [`super::engine`].

pub mod averaging;
pub mod damping;
pub mod drag;
pub mod exchange;
pub mod smoothing;
