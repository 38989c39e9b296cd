//! The `[domain]` and `[solver]` tables of a Lagrangian scene, typed and checked.

use std::path::Path;

use saltus_core::scene::{check, domain_and_solver, Scene};
use saltus_core::{Error, ParamRange};
use serde::{Deserialize, Serialize};

use super::contact::ContactModel;

/// What is below the particles.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Bottom {
    /// a layer of fixed particles from a random deposition (Maurin 2015 section IV), above
    /// a flat wall at z = 0
    #[default]
    Rough,
    /// a flat frictional wall at z = 0
    Wall,
    /// nothing (free fall)
    None,
    /// periodic in z with period `domain.height`
    Periodic,
}

/// How the particles start.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Initial {
    /// a bed deposited under gravity (jittered lattice released and settled for
    /// `solver.settle_time`)
    #[default]
    Bed,
    /// a homogeneous gas: cubic lattice at `gas_phi` with Gaussian velocities of
    /// temperature `gas_temperature`
    Gas,
    /// the particles listed in `[[domain.particle]]`
    List,
}

/// How the fluid acts.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum FluidMode {
    /// drag and buoyancy, the column solved every `fluid_period` (Maurin 2015)
    #[default]
    Coupled,
    /// drag and buoyancy from a fluid at rest (the column is not solved)
    Still,
    /// dry granular: no drag, no buoyancy
    Off,
}

/// Where the free surface is put.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Surface {
    /// `water_depth` above the surface of the deposited bed, measured after the
    /// deposition (the level where the packing falls to half its bulk value): the water
    /// depth of the Shields number is the one asked whatever the packing of the deposit
    #[default]
    Deposit,
    /// `bed_height + water_depth` above the top of the rough layer
    Nominal,
}

/// One particle of `initial = "list"`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ParticleSpec {
    /// centre (m)
    pub position: [f64; 3],
    /// velocity (m/s)
    #[serde(default)]
    pub velocity: [f64; 3],
    /// angular velocity (rad/s)
    #[serde(default)]
    pub angular_velocity: [f64; 3],
    /// fixed in space
    #[serde(default)]
    pub fixed: bool,
}

/// `[domain]` of a Lagrangian scene. Lengths in metres.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Domain {
    /// streamwise period L_x (m)
    pub length: f64,
    /// spanwise period L_y (m), or channel width with `side_walls`
    pub width: f64,
    /// flat frictional walls at y = 0 and y = width instead of a periodic y (quasi-2D
    /// channels)
    #[serde(default)]
    pub side_walls: bool,
    /// what is below the particles
    #[serde(default)]
    pub bottom: Bottom,
    /// z period (bottom = "periodic") or height of the box the gas fills (m)
    #[serde(default)]
    pub height: f64,
    /// how particles start
    #[serde(default)]
    pub initial: Initial,
    /// thickness of the mobile bed at rest (m), above the rough layer; sets the number of
    /// mobile particles with `bed_phi`
    #[serde(default)]
    pub bed_height: f64,
    /// packing used to count the particles of the bed
    #[serde(default = "default_bed_phi")]
    pub bed_phi: f64,
    /// number of mobile particles; overrides the count from `bed_height` (bed) or
    /// `gas_phi` (gas)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particles: Option<usize>,
    /// thickness of the fixed rough layer, in particle diameters
    #[serde(default = "default_rough_layer")]
    pub rough_layer: f64,
    /// clear water above the bed at rest (m); the fluid column spans bed_height +
    /// water_depth from the top of the rough layer (z = rough_layer d)
    #[serde(default)]
    pub water_depth: f64,
    /// cells of the fluid column (its nominal height bed_height + water_depth; with
    /// `surface = "deposit"` the cell size is kept and the count follows the column)
    #[serde(default = "default_cells")]
    pub cells: usize,
    /// where the free surface is put (deposited beds)
    #[serde(default)]
    pub surface: Surface,
    /// volume fraction of the gas (initial = "gas")
    #[serde(default)]
    pub gas_phi: f64,
    /// granular temperature of the gas (m^2/s^2)
    #[serde(default)]
    pub gas_temperature: f64,
    /// particles of `initial = "list"`
    #[serde(default, rename = "particle", skip_serializing_if = "Vec::is_empty")]
    pub particle_list: Vec<ParticleSpec>,
}

fn default_bed_phi() -> f64 {
    0.6
}
fn default_rough_layer() -> f64 {
    1.0
}
fn default_cells() -> usize {
    100
}

/// `[solver]` of `type = "lagrangian"`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// solver name, `lagrangian`
    #[serde(rename = "type")]
    pub kind: String,
    /// simulated time of the run after the deposition (s)
    pub end_time: f64,
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
    /// normal restitution coefficient e
    pub restitution: f64,
    /// particle friction coefficient mu_p
    pub friction: f64,
    /// time step over the contact time pi sqrt(m / (2 k_n)) (linear) or the Rayleigh time
    /// (Hertz)
    pub dt_safety: f64,
    /// Verlet skin over d
    pub skin: f64,
    /// fluid coupling
    pub fluid: FluidMode,
    /// fluid resolution period tau_f (s)
    pub fluid_period: f64,
    /// deposition time before the flow starts, fluid at rest (s)
    pub settle_time: f64,
    /// time after which profiles are averaged (s)
    pub stats_start: f64,
    /// averaging window of the steady-state test (s)
    pub steady_window: f64,
    /// steady when the window-averaged transport rate changes by less than this
    /// fraction between consecutive windows
    pub steady_tolerance: f64,
    /// consecutive windows under the tolerance
    pub steady_windows: usize,
    /// stop as soon as the run is steady
    pub stop_when_steady: bool,
    /// threads (0: all cores)
    pub threads: usize,
    /// period of VTK particle snapshots (s); 0: none
    pub vtk_period: f64,
    /// cap on DEM steps
    pub max_steps: u64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            kind: "lagrangian".into(),
            end_time: 10.0,
            contact: ContactModel::Linear,
            stiffness: 1.0e4,
            tangential_ratio: 1.0,
            young: 1.0e7,
            poisson: 0.3,
            restitution: 0.7,
            friction: 0.4,
            dt_safety: 0.05,
            skin: 0.1,
            fluid: FluidMode::Coupled,
            fluid_period: 1.0e-2,
            settle_time: 0.5,
            stats_start: 0.0,
            steady_window: 1.0,
            steady_tolerance: 0.05,
            steady_windows: 3,
            stop_when_steady: false,
            threads: 0,
            vtk_period: 0.0,
            max_steps: 1_000_000_000_000,
        }
    }
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
    /// Read `[domain]` and `[solver]` of `scene`, with errors that name the file and key.
    pub fn from_scene(scene: &Scene) -> Result<Config, Error> {
        let file = scene.path.as_path();
        let (domain, settings): (Domain, Settings) =
            domain_and_solver(scene, "a Lagrangian scene needs at least length and width")?;
        let cfg = Config { domain, settings };
        cfg.check(file, scene.particles.diameter)?;
        Ok(cfg)
    }

    fn check(&self, file: &Path, d: f64) -> Result<(), Error> {
        let key = |k: &str, m: String| Error::Key { file: file.into(), key: k.into(), message: m };
        let dm = &self.domain;
        let s = &self.settings;
        let cut = d * (1.0 + s.skin);
        // minimum image: a particle must not meet two images of another
        check(file, "domain.length", dm.length, ParamRange::closed(2.0 * cut + 1e-12, f64::MAX))?;
        if dm.side_walls {
            check(file, "domain.width", dm.width, ParamRange::closed(d, f64::MAX))?;
        } else {
            check(file, "domain.width", dm.width, ParamRange::closed(2.0 * cut + 1e-12, f64::MAX))?;
        }
        if dm.bottom == Bottom::Periodic {
            check(file, "domain.height", dm.height, ParamRange::closed(2.0 * cut + 1e-12, f64::MAX))?;
            if s.fluid == FluidMode::Coupled {
                return Err(key(
                    "solver.fluid",
                    "a z-periodic box has no fluid column; use fluid = \"off\" or \"still\"".into(),
                ));
            }
        }
        check(file, "domain.bed_height", dm.bed_height, ParamRange::non_negative())?;
        check(file, "domain.bed_phi", dm.bed_phi, ParamRange::open_closed(0.0, 0.74))?;
        check(file, "domain.rough_layer", dm.rough_layer, ParamRange::closed(0.5, 10.0))?;
        check(file, "domain.water_depth", dm.water_depth, ParamRange::non_negative())?;
        check(file, "domain.cells", dm.cells as f64, ParamRange::closed(2.0, 1_000_000.0))?;
        match dm.initial {
            Initial::Bed => {
                if dm.particles.is_none() && dm.bed_height <= 0.0 {
                    return Err(key(
                        "domain.bed_height",
                        "initial = \"bed\" needs bed_height > 0 (m) or particles = N".into(),
                    ));
                }
                if dm.bottom == Bottom::None || dm.bottom == Bottom::Periodic {
                    return Err(key("domain.bottom", "a deposited bed needs bottom = \"rough\" or \"wall\"".into()));
                }
            }
            Initial::Gas => {
                check(file, "domain.gas_phi", dm.gas_phi, ParamRange::open(0.0, 0.5))?;
                check(file, "domain.gas_temperature", dm.gas_temperature, ParamRange::positive())?;
                check(file, "domain.height", dm.height, ParamRange::closed(2.0 * cut + 1e-12, f64::MAX))?;
            }
            Initial::List => {
                if dm.particle_list.is_empty() {
                    return Err(key("domain.particle", "initial = \"list\" needs [[domain.particle]] entries".into()));
                }
                for (k, p) in dm.particle_list.iter().enumerate() {
                    for v in p.position.iter().chain(&p.velocity).chain(&p.angular_velocity) {
                        if !v.is_finite() {
                            return Err(key(&format!("domain.particle[{k}]"), "values must be finite".into()));
                        }
                    }
                }
                let mut fixed_seen = false;
                for (k, p) in dm.particle_list.iter().enumerate() {
                    if p.fixed {
                        fixed_seen = true;
                    } else if fixed_seen {
                        return Err(key(
                            &format!("domain.particle[{k}]"),
                            "list mobile particles before fixed ones".into(),
                        ));
                    }
                }
            }
        }
        if s.fluid != FluidMode::Off && dm.bottom != Bottom::Periodic {
            let h = self.column_height();
            if h <= 0.0 {
                return Err(key("domain.water_depth", "the fluid column height must be > 0".into()));
            }
        }
        check(file, "solver.end_time", s.end_time, ParamRange::positive())?;
        check(file, "solver.stiffness", s.stiffness, ParamRange::positive())?;
        check(file, "solver.tangential_ratio", s.tangential_ratio, ParamRange::closed(0.0, 10.0))?;
        check(file, "solver.young", s.young, ParamRange::positive())?;
        check(file, "solver.poisson", s.poisson, ParamRange::closed(0.0, 0.5))?;
        check(file, "solver.restitution", s.restitution, ParamRange::open_closed(0.0, 1.0))?;
        check(file, "solver.friction", s.friction, ParamRange::non_negative())?;
        check(file, "solver.dt_safety", s.dt_safety, ParamRange::open_closed(0.0, 0.3))?;
        check(file, "solver.skin", s.skin, ParamRange::open_closed(0.0, 2.0))?;
        check(file, "solver.fluid_period", s.fluid_period, ParamRange::positive())?;
        check(file, "solver.settle_time", s.settle_time, ParamRange::non_negative())?;
        check(file, "solver.stats_start", s.stats_start, ParamRange::non_negative())?;
        check(file, "solver.steady_window", s.steady_window, ParamRange::positive())?;
        check(file, "solver.steady_tolerance", s.steady_tolerance, ParamRange::non_negative())?;
        check(file, "solver.steady_windows", s.steady_windows as f64, ParamRange::closed(1.0, 1e9))?;
        check(file, "solver.threads", s.threads as f64, ParamRange::closed(0.0, 1024.0))?;
        check(file, "solver.vtk_period", s.vtk_period, ParamRange::non_negative())?;
        check(file, "solver.max_steps", s.max_steps as f64, ParamRange::closed(1.0, 1e15))?;
        Ok(())
    }

    /// Height of the rough layer (m): `rough_layer` d with a rough bottom, else 0. The
    /// fluid column starts there.
    pub fn rough_height(&self, d: f64) -> f64 {
        if self.domain.bottom == Bottom::Rough {
            self.domain.rough_layer * d
        } else {
            0.0
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
