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

    /// The two-equation (k, omega) face of a transport closure, `None` for algebraic ones.
    /// A closure whose [`Turbulence::transported`] is `["k", "omega"]` returns `Some`.
    fn as_two_equation(&self) -> Option<&dyn TwoEquation> {
        None
    }
}

/// What a two-equation closure needs from the solver beyond the [`ColumnView`], per cell
/// unless stated. `col.transported` holds `[k, omega]`.
#[derive(Clone, Copy, Debug)]
pub struct TwoEquationInput<'a> {
    /// the column, with `transported = [k (m^2/s^2), omega (1/s)]`
    pub col: ColumnView<'a>,
    /// interphase drag coefficient per unit particle volume, beta of Cheng et al. eq 23
    /// (kg m^-3 s^-1): drag force per unit mixture volume = phi beta (u_f - u_p); the
    /// particle response time is rho_p / beta
    pub drag: &'a [f64],
    /// wall-normal volume-fraction gradient d phi / dz (1/m)
    pub dphidz: &'a [f64],
    /// fluid density rho_f (kg/m^3)
    pub fluid_density: f64,
    /// particle density rho_p (kg/m^3)
    pub particle_density: f64,
    /// wall-normal gravity g cos(alpha) (m/s^2), pointing down (towards z = 0)
    pub gravity_normal: f64,
    /// friction velocity of the forcing at the bed surface (m/s), for the in-bed omega
    pub friction_velocity: f64,
}

/// Terms of the k and omega equations per cell, structure of arrays, in the form
/// d q / dt = d/dz (D dq/dz) + source - sink q, with source >= 0 and sink >= 0 so that an
/// implicit sink keeps q positive under any time step.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct TwoEquationTerms {
    /// explicit source of k (m^2/s^3), >= 0
    pub k_source: Vec<f64>,
    /// implicit sink rate of k (1/s), >= 0
    pub k_sink: Vec<f64>,
    /// diffusivity of k (m^2/s)
    pub k_diffusivity: Vec<f64>,
    /// explicit source of omega (1/s^2), >= 0
    pub omega_source: Vec<f64>,
    /// implicit sink rate of omega (1/s), >= 0
    pub omega_sink: Vec<f64>,
    /// diffusivity of omega (m^2/s)
    pub omega_diffusivity: Vec<f64>,
}

impl TwoEquationTerms {
    /// Zeroed terms for `n` cells.
    pub fn new(n: usize) -> Self {
        let v = || vec![0.0; n];
        Self {
            k_source: v(),
            k_sink: v(),
            k_diffusivity: v(),
            omega_source: v(),
            omega_sink: v(),
            omega_diffusivity: v(),
        }
    }
}

/// Where and how the bottom-wall value of omega is imposed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallOmega {
    /// omega fixed in the first cell (its centre at distance z_o from the wall)
    FirstCell,
    /// omega fixed at the wall face z = 0
    WallFace,
}

/// A two-equation (k, omega) turbulence closure: the physics of the source terms, the
/// eddy viscosity and the wall values. The transport (time stepping, diffusion,
/// boundary rows) is the solver's.
pub trait TwoEquation: Send + Sync {
    /// Source, sink rate and diffusivity of k and omega in every cell.
    fn terms(&self, input: &TwoEquationInput<'_>, out: &mut TwoEquationTerms);

    /// Eddy viscosity (m^2/s) of a point with turbulent kinetic energy `k` and specific
    /// dissipation `omega` in a fluid of kinematic viscosity `nu`.
    fn eddy_viscosity_of(&self, k: f64, omega: f64, nu: f64) -> f64;

    /// Where [`TwoEquation::wall_omega`] applies.
    fn wall_location(&self) -> WallOmega;

    /// Bottom-wall value of omega (1/s): at a cell centre a distance `z0` from the wall
    /// ([`WallOmega::FirstCell`], `u_star` the wall friction velocity
    /// sqrt((nu + nu_t) |du/dz|) there) or at the wall face ([`WallOmega::WallFace`],
    /// `u_star` the friction velocity of the forcing); `diameter` is the particle diameter.
    fn wall_omega(&self, z0: f64, u_star: f64, nu: f64, diameter: f64) -> f64;

    /// Uniform initial (k, omega) of a column of height `height` driven at the friction
    /// velocity `u_star`.
    fn initial_state(&self, u_star: f64, height: f64, nu: f64) -> (f64, f64);

    /// Initial (k, omega) of a cell at volume fraction `phi` (`diameter` the particle
    /// diameter): a closure may damp the turbulence of a packed bed at start-up; the
    /// uniform [`TwoEquation::initial_state`] by default.
    fn initial_state_at(&self, phi: f64, u_star: f64, height: f64, nu: f64, diameter: f64) -> (f64, f64) {
        let _ = (phi, diameter);
        self.initial_state(u_star, height, nu)
    }

    /// Start t_0 (s) of the time average of the phases' relative velocity that sets the
    /// drag coefficient of the drag-damping terms (Cheng et al. 2018 eq 24), or `None` for
    /// the current relative velocity. A solver whose particles fluctuate about their mean
    /// (the DEM) averages from t_0; a steady continuum column has nothing to average.
    fn slip_average_start(&self) -> Option<f64> {
        None
    }
}
