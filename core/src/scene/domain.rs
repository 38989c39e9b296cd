//! `[domain]`: the physical column both solvers share.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::check;
use crate::error::{Error, Result};
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
    /// cells of the Eulerian column; default: cells of d/4 over the column (or of
    /// `cell_size`)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cells: Option<usize>,
    /// size of the cells of a uniform grid instead of their number, in m (a number) or in
    /// grain diameters (`"0.25 d"` or `"d/4"`): `cells` (and the DEM's fluid cells when
    /// not given) follow the column's height, so that a sweep over the depth keeps the
    /// resolution
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cell_size: Option<CellSize>,
    /// ratio of the heights of successive Eulerian cells from the bottom, in [1, 1.2]
    #[serde(default = "unit_stretching")]
    pub stretching: f64,
    /// top boundary
    #[serde(default)]
    pub top: Top,
    /// lid velocity (m/s) when `top = "lid"`
    #[serde(default)]
    pub lid_velocity: f64,
    /// a profiles CSV (z, u_f; optional phi, u_p, theta_g) the Eulerian column starts from
    /// instead of rest, relative to the scene; absolute once loaded
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_profiles: Option<String>,
    /// the columns of `initial_profiles` as loaded ([`super::initial::read`]): read once,
    /// when the scene is
    #[serde(skip)]
    pub initial_columns: Vec<(String, Vec<f64>)>,
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
            cell_size: None,
            stretching: 1.0,
            top: Top::FreeSurface,
            lid_velocity: 0.0,
            initial_profiles: None,
            initial_columns: Vec::new(),
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

    /// Cells of `size` over the column, at least `least`.
    pub fn cells_of(&self, size: f64, least: usize) -> usize {
        let n = (self.height() / size).round();
        // a count past any cap stays past it rather than wrapping
        if n.is_finite() && n < 1e15 {
            (n as usize).max(least)
        } else {
            usize::MAX
        }
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
        if let Some(c) = &self.cell_size {
            let (key, v) = match c {
                CellSize::Metres(m) => ("domain.cell_size", *m),
                CellSize::Diameters(x) => ("domain.cell_size (in diameters)", *x),
            };
            check(f, key, v, ParamRange::open_closed(0.0, MAX_HEIGHT))?;
            if self.stretching != 1.0 {
                return Err(Error::Key {
                    file: f.into(),
                    key: "domain.cell_size".into(),
                    message: format!(
                        "sizes the cells of a uniform grid, and domain.stretching = {} stretches it: give domain.cells instead",
                        self.stretching
                    ),
                });
            }
        }
        check(f, "domain.lid_velocity", self.lid_velocity, ParamRange::closed(-1e3, 1e3))
    }
}

/// `domain.cell_size`: metres, or grain diameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellSize {
    /// in m
    Metres(f64),
    /// in grain diameters
    Diameters(f64),
}

impl CellSize {
    /// The size in m for grains of diameter `d`.
    pub fn metres(self, d: f64) -> f64 {
        match self {
            CellSize::Metres(m) => m,
            CellSize::Diameters(x) => x * d,
        }
    }

    /// Read `"0.25 d"`, `"0.25d"` or `"d/4"`.
    fn parse_diameters(text: &str) -> Option<f64> {
        let t = text.trim();
        let x = if let Some(n) = t.strip_prefix("d/") {
            1.0 / n.trim().parse::<f64>().ok()?
        } else {
            t.strip_suffix('d')?.trim().parse::<f64>().ok()?
        };
        x.is_finite().then_some(x)
    }
}

impl Serialize for CellSize {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            CellSize::Metres(m) => s.serialize_f64(*m),
            CellSize::Diameters(x) => s.serialize_str(&format!("{x:?} d")),
        }
    }
}

impl<'de> Deserialize<'de> for CellSize {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> std::result::Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Number(f64),
            Text(String),
        }
        let bad = || {
            serde::de::Error::custom(
                "expected a size in m (a number, e.g. 1.5e-3) or in grain diameters (a string, \"0.25 d\" or \"d/4\")",
            )
        };
        match Raw::deserialize(de).map_err(|_| bad())? {
            Raw::Number(m) => Ok(CellSize::Metres(m)),
            Raw::Text(t) => CellSize::parse_diameters(&t).map(CellSize::Diameters).ok_or_else(bad),
        }
    }
}
