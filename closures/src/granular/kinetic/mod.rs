//! Parts of the kinetic theory of `frictional_collisional`: radial distribution g0,
//! Garzo-Dufty coefficients, effective restitution, saltation correction and drag
//! dissipation.

pub mod drag_dissipation;
pub mod garzo_dufty;
pub mod radial_distribution;
pub mod restitution;
pub mod saltation;

pub use drag_dissipation::DragDissipation;
pub use radial_distribution::{
    ChialvoSundaresanFrictionG0, ChialvoSundaresanG0, ChialvoSundaresanPowerG0, RadialDistribution, TorquatoG0,
};
pub use restitution::{JenkinsZhang, RestitutionModel};
pub use saltation::Saltation;
