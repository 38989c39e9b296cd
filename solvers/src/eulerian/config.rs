//! The Eulerian view of a scene: `[domain]` and `[solver.eulerian]`, typed and checked
//! at load by [`saltus_core::scene`]; here only resolved into the numbers the solver uses.

use saltus_core::scene::Scene;
use saltus_core::Error;

pub use saltus_core::scene::{EulerianSettings as Settings, Top};

/// The column, resolved. Heights in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    /// thickness of the initial sediment bed at rest (m); 0 for clear fluid
    pub bed_height: f64,
    /// volume fraction of the initial bed; `None` leaves the solver's default (0.61, or
    /// 0.95 of the closure's maximum packing when that is lower)
    pub bed_phi: Option<f64>,
    /// uniform volume fraction of a suspension above the bed at start (hindered settling)
    pub suspension_phi: f64,
    /// clear fluid above the initial bed (m); the column height is bed_height + water_depth
    pub water_depth: f64,
    /// number of cells
    pub cells: usize,
    /// ratio of the heights of successive cells from the bottom, dz_(i+1) = r dz_i: 1 is a
    /// uniform grid, r > 1 refines towards the bottom wall (a smooth-wall channel needs the
    /// near-wall 1/z^2 of omega resolved, see docs/benchmarks.md); in [1, 1.2], where the
    /// linear face interpolation of the solver keeps its second-order error small
    pub stretching: f64,
    /// top boundary
    pub top: Top,
    /// lid velocity (m/s) when `top = "lid"`
    pub lid_velocity: f64,
}

/// Checked configuration of one Eulerian run.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// the column
    pub domain: Domain,
    /// the numerics
    pub settings: Settings,
}

impl Config {
    /// The Eulerian configuration of `scene`, whatever its active solver. The scene was
    /// checked when loaded; a cell count it could not default is refused here.
    pub fn from_scene(scene: &Scene) -> Result<Config, Error> {
        let d = &scene.domain;
        let cells = d.cells.ok_or_else(|| Error::Key {
            file: scene.path.clone(),
            key: "domain.cells".into(),
            message: "missing, and the default d/4 grid is too fine; give it".into(),
        })?;
        let domain = Domain {
            bed_height: d.bed_height,
            bed_phi: d.bed_phi,
            suspension_phi: d.suspension_phi,
            water_depth: d.water_depth,
            cells,
            stretching: d.stretching,
            top: d.top,
            lid_velocity: d.lid_velocity,
        };
        Ok(Config { domain, settings: scene.solver.eulerian.clone() })
    }
}
