//! Flat walls and the contact slots a mobile particle records besides its pairs.

use super::cylinders::MAX_TOUCHES;

/// A flat wall at `position` along `axis`; particles live on the side `sign` (+1: above).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Wall {
    /// 0, 1 or 2 (x, y, z)
    pub axis: usize,
    /// coordinate of the plane (m)
    pub position: f64,
    /// +1 if particles are at larger coordinates, -1 otherwise
    pub sign: f64,
}

/// Most walls a scene can have (bottom and two side walls).
pub const MAX_WALLS: usize = 3;

/// Contacts of one mobile particle recorded for the granular fields besides its pairs:
/// the walls', then the half-cylinders' ([`super::cylinders`]).
pub const RECORD_SLOTS: usize = MAX_WALLS + MAX_TOUCHES;
