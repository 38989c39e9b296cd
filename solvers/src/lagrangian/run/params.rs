//! What a scene resolves to for the Lagrangian solver: read-only for the whole run, built
//! again from the scene by a restart (never part of a checkpoint).

use saltus_core::scene::Scene;
use saltus_core::{DragLaw, EffectiveViscosity, Fluctuation, Hindrance, Turbulence};

use super::config::Config;
use super::setup::Material;
use crate::column::ColumnParams;
use crate::lagrangian::coupling::drag::DragModels;
use crate::measures::transport_scales::TransportScales;

/// The resolved parameters of a run.
pub struct Params<'a> {
    pub(crate) scene: &'a Scene,
    pub(crate) cfg: Config,
    pub(crate) viscosity: &'a dyn EffectiveViscosity,
    pub(crate) turbulence: &'a dyn Turbulence,
    pub(crate) drag: &'a dyn DragLaw,
    pub(crate) hindrance: &'a dyn Hindrance,
    /// the fluctuation closure when it is active
    pub(crate) fluctuation: Option<&'a dyn Fluctuation>,
    /// the hindrance does not see Re_p: its factor is taken once per cell at each update
    pub(crate) re_free_hindrance: bool,
    /// DEM steps per fluid period
    pub(crate) fluid_every: u64,
    /// DEM steps of the deposition
    pub(crate) settle_total: u64,
    /// body acceleration of the flow (the deposition runs without the streamwise pull)
    pub(crate) flow_body: [f64; 3],
    pub(crate) mat: Material,
    /// the scales of qs*, Shields and the nominal Shields number of the summary and the
    /// time series
    pub(crate) scales: TransportScales,
    pub(crate) seed: u64,
    /// the fluid column's parameters, when coupled (a deposit-fitted column is built anew
    /// from them)
    pub(crate) column_params: Option<ColumnParams>,
    /// Haff's constant sqrt(pi) d / (4 (1 - e^2) phi g0) (s m/s) of a homogeneous cooling
    /// scene ([`crate::lagrangian::stats::cooling::Cooling`]), `None` for any other
    pub(crate) haff: Option<f64>,
}

impl<'a> Params<'a> {
    /// The closures the drag evaluation calls.
    pub(crate) fn models(&self) -> DragModels<'a> {
        DragModels {
            drag: self.drag,
            hindrance: self.hindrance,
            fluctuation: self.fluctuation,
            velocity: self.cfg.settings.numerics.drag_velocity,
        }
    }
}
