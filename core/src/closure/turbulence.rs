//! Turbulence closures of the fluid column.

use crate::needs::Needs;
use crate::param::Describe;

/// A view of the 1D column given to turbulence closures. Cells are ordered from the
/// bottom wall (z = 0) upwards; `z` are cell centres and `dz` cell widths.
#[derive(Clone, Copy, Debug)]
pub struct ColumnView<'a> {
    /// cell centres (m), from the bottom wall
    pub z: &'a [f64],
    /// cell widths (m)
    pub dz: &'a [f64],
    /// solid volume fraction per cell
    pub phi: &'a [f64],
    /// fluid shear rate d u_f / dz per cell (1/s)
    pub dudz: &'a [f64],
    /// particle diameter (m)
    pub diameter: f64,
    /// clear-fluid kinematic viscosity (m^2/s)
    pub nu_f: f64,
    /// fields transported by the closure itself (e.g. k, omega), in the order of
    /// [`Turbulence::transported`]; empty for algebraic closures
    pub transported: &'a [&'a [f64]],
}

impl ColumnView<'_> {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.z.len()
    }
    /// Whether the column has no cell.
    pub fn is_empty(&self) -> bool {
        self.z.is_empty()
    }
}

/// A turbulence closure. Algebraic closures (laminar, mixing length) give the eddy
/// viscosity from the column state; transport closures (k-omega) additionally name the
/// fields they transport, which the column solver then allocates and advances; a scene
/// without such a closure carries no such field.
#[typetag::serde(tag = "type")]
pub trait Turbulence: Describe + Send + Sync + std::fmt::Debug {
    /// Fields this closure makes available to other closures.
    fn provides(&self) -> Needs;

    /// Names of the fields the closure transports (empty for algebraic closures).
    fn transported(&self) -> &'static [&'static str] {
        &[]
    }

    /// Mixing length per cell (m); zero for laminar flow.
    fn mixing_length(&self, col: &ColumnView<'_>, out: &mut [f64]);

    /// Eddy viscosity nu_t from a mixing length and a shear rate (Prandtl):
    /// nu_t = l_m^2 |du/dz|.
    fn eddy_viscosity_point(&self, l_m: f64, dudz: f64) -> f64 {
        l_m * l_m * dudz.abs()
    }

    /// Eddy viscosity per cell (m^2/s).
    fn eddy_viscosity(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        self.mixing_length(col, out);
        for (o, &g) in out.iter_mut().zip(col.dudz) {
            *o = self.eddy_viscosity_point(*o, g);
        }
    }
}
