//! The Lagrangian view of a scene: `[domain]`, `[particles]` and `[solver.lagrangian]`,
//! typed and checked at load by [`saltus_core::scene`]; here only gathered into the
//! numbers the DEM uses.

use saltus_core::scene::{LagrangianSettings, Scene, DEM_BED_PHI};
use saltus_core::Error;

use crate::lagrangian::engine::contact::{ContactModel, NormalForce, TangentialHistory};

pub use saltus_core::scene::{Bottom, FluidMode, Initial, ParticleSpec, Surface};

/// What the DEM resolves of the box and the bed: the values whose defaults depend on the
/// case. The rest of its geometry (walls, bottom, initial state, gas, particle list) is
/// read from `[solver.lagrangian]` as resolved ([`Settings::numerics`]). Lengths in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    /// streamwise period L_x (m)
    pub length: f64,
    /// spanwise period L_y (m), or channel width with `side_walls`
    pub width: f64,
    /// thickness of the mobile bed at rest (m), above the rough layer
    pub bed_height: f64,
    /// packing used to count the particles of the bed
    pub bed_phi: f64,
    /// clear water above the bed at rest (m)
    pub water_depth: f64,
    /// cells of the fluid column
    pub cells: usize,
}

/// The DEM's numerics and contact law.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// `[solver.lagrangian]` as resolved at load (every default filled in)
    pub numerics: LagrangianSettings,
    /// contact law
    pub contact: ContactModel,
    /// normal stiffness k_n of the linear law (N/m)
    pub stiffness: f64,
    /// k_t / k_n of the linear law
    pub tangential_ratio: f64,
    /// Young modulus of the Hertz law (Pa)
    pub young: f64,
    /// Poisson ratio of the Hertz law
    pub poisson: f64,
    /// whether the normal force may pull
    pub normal_force: NormalForce,
    /// how the tangential spring follows the contact
    pub tangential_history: TangentialHistory,
    /// normal restitution coefficient e
    pub restitution: f64,
    /// particle friction coefficient mu_p
    pub friction: f64,
    /// deposition time before the flow starts, fluid at rest (s); 0 without a deposition
    pub settle_time: f64,
}

/// Checked configuration of one Lagrangian run.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// the box and the particles
    pub domain: Domain,
    /// the numerics
    pub settings: Settings,
}

impl Config {
    /// The DEM configuration of `scene`, whatever its active solver. A derived default
    /// the scene could not fill (no gravity, say) is refused here with its key.
    pub fn from_scene(scene: &Scene) -> Result<Config, Error> {
        let missing = |key: &str| Error::Key {
            file: scene.path.clone(),
            key: key.into(),
            message: "missing, and its default cannot be derived for this case; give it".into(),
        };
        let l = &scene.solver.lagrangian;
        let p = &scene.particles;
        let dm = &scene.domain;
        let initial_bed = l.initial == Initial::Bed;
        let domain = Domain {
            length: l.length.ok_or_else(|| missing("solver.lagrangian.length"))?,
            width: l.width.ok_or_else(|| missing("solver.lagrangian.width"))?,
            bed_height: dm.bed_height,
            bed_phi: dm.bed_phi.unwrap_or(DEM_BED_PHI),
            water_depth: dm.water_depth,
            cells: l.cells.ok_or_else(|| missing("solver.lagrangian.cells"))?,
        };
        let linear = p.contact.law == ContactModel::Linear;
        let settings = Settings {
            numerics: l.clone(),
            contact: p.contact.law,
            // the Hertz law has no k_n: any positive number keeps the struct total
            stiffness: match p.contact.stiffness {
                Some(k) => k,
                None if linear => return Err(missing("particles.contact.stiffness")),
                None => 1.0,
            },
            tangential_ratio: p.contact.tangential_ratio,
            young: p.contact.young,
            poisson: p.contact.poisson,
            normal_force: p.contact.normal_force,
            tangential_history: p.contact.tangential_history,
            restitution: p.restitution,
            friction: p.friction,
            settle_time: match l.settle_time {
                Some(t) => t,
                None if initial_bed => return Err(missing("solver.lagrangian.settle_time")),
                None => 0.0,
            },
        };
        Ok(Config { domain, settings })
    }

    /// Height of the rough layer (m): `rough_layer` d with a rough bottom, d (the mean
    /// elevation of its elements) with a Frey bottom, else 0. The fluid column starts
    /// there.
    pub fn rough_height(&self, d: f64) -> f64 {
        let l = &self.settings.numerics;
        match l.bottom {
            Bottom::Rough => l.rough_layer * d,
            b if b.is_frey() => d,
            _ => 0.0,
        }
    }

    /// Nominal bed surface at rest above the column bottom (m): bed_height.
    pub fn bed_surface(&self) -> f64 {
        self.domain.bed_height
    }

    /// Height of the fluid column (m): bed_height + water_depth, from the top of the rough
    /// layer (Chassagne 2023 figure 1: H_f = H_bed + h_w above the fixed particles).
    pub fn column_height(&self) -> f64 {
        self.domain.bed_height + self.domain.water_depth
    }
}
