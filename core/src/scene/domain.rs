//! `[domain]`: the physical column both solvers share.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::check;
use crate::error::Result;
use crate::param::ParamRange;

/// Top boundary of the column.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Top {
    /// zero shear stress (open channel)
    #[default]
    FreeSurface,
    /// moving lid at `lid_velocity` (Couette)
    Lid,
    /// symmetry plane (channel centreline)
    Symmetry,
}

/// Largest thickness of bed or water (m): far above any column the solvers can grid,
/// low enough that heights, cell sizes and pressures stay finite.
pub const MAX_HEIGHT: f64 = 1.0e3;

/// Most cells of the Eulerian column.
pub const MAX_CELLS: usize = 100_000;
/// Decades that the cell widths of a stretched grid may span (largest over first, r^(n-1)
/// at most 1e4; see the check of the Eulerian scene).
pub const MAX_STRETCH_DECADES: f64 = 4.0;

/// Cells per grain diameter of the default Eulerian grid (d/4, Chassagne et al. 2023).
pub const CELLS_PER_DIAMETER: f64 = 4.0;

/// `[domain]`: the column. Heights in metres.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Domain {
    /// thickness of the sediment bed at rest (m); 0 for clear fluid
    #[serde(default)]
    pub bed_height: f64,
    /// volume fraction of the bed at rest. Each solver keeps its validated default:
    /// Eulerian 0.61 (Chassagne 2023 set-up, 0.95 of the closure's maximum packing when
    /// that is lower), Lagrangian 0.6 (packing used to count the particles of the bed);
    /// resolved for the active solver at load
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bed_phi: Option<f64>,
    /// uniform volume fraction of a suspension above the bed at start (Eulerian)
    #[serde(default)]
    pub suspension_phi: f64,
    /// clear fluid above the bed at rest (m); the column height is bed_height + water_depth
    #[serde(default)]
    pub water_depth: f64,
    /// cells of the Eulerian column; default: cells of d/4 over the column
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cells: Option<usize>,
    /// ratio of the heights of successive Eulerian cells from the bottom, in [1, 1.2]
    #[serde(default = "unit_stretching")]
    pub stretching: f64,
    /// top boundary
    #[serde(default)]
    pub top: Top,
    /// lid velocity (m/s) when `top = "lid"`
    #[serde(default)]
    pub lid_velocity: f64,
}

fn unit_stretching() -> f64 {
    1.0
}

impl Default for Domain {
    fn default() -> Self {
        Self {
            bed_height: 0.0,
            bed_phi: None,
            suspension_phi: 0.0,
            water_depth: 0.0,
            cells: None,
            stretching: 1.0,
            top: Top::FreeSurface,
            lid_velocity: 0.0,
        }
    }
}

impl Domain {
    /// Column height bed_height + water_depth (m).
    pub fn height(&self) -> f64 {
        self.bed_height + self.water_depth
    }

    /// Default cell count: cells of d/4 over the column, at least 4.
    pub fn default_cells(&self, d: f64) -> usize {
        ((self.height() * CELLS_PER_DIAMETER / d).round() as usize).max(4)
    }

    /// Ranges that hold whatever the solver.
    pub(super) fn check(&self, f: &Path) -> Result<()> {
        check(f, "domain.bed_height", self.bed_height, ParamRange::closed(0.0, MAX_HEIGHT))?;
        check(f, "domain.water_depth", self.water_depth, ParamRange::closed(0.0, MAX_HEIGHT))?;
        if let Some(p) = self.bed_phi {
            check(f, "domain.bed_phi", p, ParamRange::open_closed(0.0, 0.74))?;
        }
        check(f, "domain.suspension_phi", self.suspension_phi, ParamRange::closed_open(0.0, 0.74))?;
        if let Some(n) = self.cells {
            check(f, "domain.cells", n as f64, ParamRange::closed(4.0, MAX_CELLS as f64))?;
        }
        check(f, "domain.stretching", self.stretching, ParamRange::closed(1.0, 1.2))?;
        check(f, "domain.lid_velocity", self.lid_velocity, ParamRange::closed(-1e3, 1e3))
    }
}
