//! `[solver.lagrangian]`: the DEM's own geometry and numerics, with defaults derived
//! from the grain size and the case where they depend on it.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{check, key_error, MAX_TIME};
use crate::error::Result;
use crate::param::ParamRange;

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
    /// periodic in z with period `height`
    Periodic,
    /// the bottom of Maurin et al. 2015's own quasi-2D runs (section III B: "the bottom
    /// made of fixed particles is randomly generated with the experimental
    /// characteristics" of section III A): fixed beads side by side, one per diameter
    /// along x (and per diameter across), centres at d plus a random elevation of the
    /// Frey set ([`FREY_LEVELS`]), above a flat wall at z = 0
    BeadRow,
    /// the bottom of Frey's experiment (Maurin et al. 2015 section III A): half-cylinders
    /// of diameter d, axes across the channel (along y), side by side along x, axes at d
    /// plus a random elevation of the Frey set ([`FREY_LEVELS`]), above a flat wall at
    /// z = 0
    HalfCylinders,
}

impl Bottom {
    /// A bottom of fixed elements at random elevations of the Frey set (`bead_row`,
    /// `half_cylinders`): the fluid column starts at their mean elevation, d.
    pub fn is_frey(&self) -> bool {
        matches!(self, Bottom::BeadRow | Bottom::HalfCylinders)
    }
}

/// Elevation levels of the Frey bottom (Maurin et al. 2015 section III A): "a random
/// elevation between -2.75 mm and 2.75 mm with steps of 0.5 mm" for d = 6 mm, i.e.
/// (k - 5.5) d / 12 for k = 0..11, drawn uniformly (scaled with d for other grains).
pub const FREY_LEVELS: usize = 12;

/// How the particles start.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Initial {
    /// a bed deposited under gravity (jittered lattice released and settled for
    /// `settle_time`)
    #[default]
    Bed,
    /// a homogeneous gas: cubic lattice at `gas_phi` with Gaussian velocities of
    /// temperature `gas_temperature`
    Gas,
    /// the particles listed in `[[solver.lagrangian.particle]]`
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

/// The fluid velocity the DEM drag of a grain sees (`drag_velocity`), and with it the
/// momentum exchange with the column (`saltus_solvers::lagrangian::averaging`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum DragVelocity {
    /// the column velocity at the grain's centre (Maurin et al. 2015 eq 11, as the
    /// reference YADE code), the column taking beta = n `<f_D>` / (u_f - `<v>`) (eq 18) with the
    /// linear coefficient where that quotient is refused
    #[default]
    Centre,
    /// the column velocity averaged over the grain with the slice volumes of the
    /// averaging (its transpose), the column taking each grain's drag linearised grain by
    /// grain: exact, implicit, nothing refused
    SphereAverage,
}

impl DragVelocity {
    /// The velocity at the centre (the default, not written in a resolved scene).
    pub fn is_centre(&self) -> bool {
        *self == DragVelocity::Centre
    }
}

/// Which volume fraction the column and the particles' hindrance read at a fluid update
/// (`phi_average`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PhiAverage {
    /// the slice volumes of the grains at the update's DEM step (Maurin et al. 2015 eq 6)
    #[default]
    Step,
    /// the mean of the slice volumes over the N_s DEM steps of the fluid period that ends
    /// at the update, phi = (1 / N_s) sum_j phi_j (Cheng, Chauchat, Hsu & Calantoni,
    /// eq 14)
    FluidPeriod,
}

impl PhiAverage {
    /// The one-step slice (the default, not written in a resolved scene).
    pub fn is_step(&self) -> bool {
        *self == PhiAverage::Step
    }
}

/// Largest diffusion length of the fluid's volume fraction, `phi_diffusion`, in grain
/// diameters (Cheng et al. take 1, after eq 17).
pub const MAX_PHI_DIFFUSION: f64 = 10.0;

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

/// Default periodic cell, in grain diameters (Maurin 2015 appendix A found 10 d to 50 d
/// converged).
pub const CELL_DIAMETERS: f64 = 20.0;
/// Default fluid cells per grain diameter (d/30, Maurin 2015 appendix A).
pub const FLUID_CELLS_PER_DIAMETER: f64 = 30.0;
/// Most particles of one DEM run.
pub const MAX_PARTICLES: f64 = 1.0e7;
/// Most cells of the DEM's fluid column.
pub const MAX_FLUID_CELLS: usize = 1_000_000;
/// Longest side of the box in grain diameters (bounds the neighbour grid).
pub const MAX_SIDE_DIAMETERS: f64 = 1.0e4;
/// Packing of the released lattice of `initial = "bed"` (cubic, spacing 1.1 d).
const LATTICE_PHI: f64 = crate::grain::sphere_volume(1.0) / (1.1 * 1.1 * 1.1);
/// Largest `size_dispersion`: the largest grain, (1 + s) d, stays below the released
/// lattice's spacing of 1.1 d.
pub const MAX_SIZE_DISPERSION: f64 = 0.09;
/// Free-fall times of the released lattice in the default settle time.
const SETTLE_FALLS: f64 = 3.0;

/// `[solver.lagrangian]`. Lengths in metres; `None` of a derived key before the scene is
/// resolved (always `Some` after, unless the default cannot be derived and the DEM is
/// not the active solver).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LagrangianSettings {
    /// simulated time of the run after the deposition (s)
    pub end_time: f64,
    /// streamwise period L_x (m); default 20 d
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// spanwise period L_y (m), or channel width with `side_walls`; default 20 d
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// flat frictional walls at y = 0 and y = width instead of a periodic y
    pub side_walls: bool,
    /// what is below the particles
    pub bottom: Bottom,
    /// z period (bottom = "periodic") or height of the box the gas fills (m)
    pub height: f64,
    /// how particles start
    pub initial: Initial,
    /// number of mobile particles; overrides the count from `domain.bed_height` (bed) or
    /// `gas_phi` (gas)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub particles: Option<usize>,
    /// size dispersion s of a deposited bed (`initial = "bed"`): the diameters of the
    /// released grains (the rough layer's among them) drawn uniformly in [(1 - s) d, (1 + s) d] (Fry et al. 2024 section II C: 5 % "to avoid
    /// crystallization"); 0: monodisperse (not written then)
    #[serde(skip_serializing_if = "super::tables::is_zero")]
    pub size_dispersion: f64,
    /// thickness of the fixed rough layer, in particle diameters
    pub rough_layer: f64,
    /// cells of the DEM's fluid column over bed_height + water_depth; default cells of
    /// d/30 (with `surface = "deposit"` the cell size is kept and the count follows)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cells: Option<usize>,
    /// where the free surface is put (deposited beds)
    pub surface: Surface,
    /// volume fraction of the gas (initial = "gas")
    pub gas_phi: f64,
    /// granular temperature of the gas (m^2/s^2)
    pub gas_temperature: f64,
    /// particles of `initial = "list"`
    #[serde(rename = "particle", skip_serializing_if = "Vec::is_empty")]
    pub particle_list: Vec<ParticleSpec>,
    /// time step over the contact time pi sqrt(m / (2 k_n)) (linear) or the Rayleigh time
    /// (Hertz)
    pub dt_safety: f64,
    /// smallest Verlet skin over d: the neighbour list widens it (up to one diameter) so
    /// that it lasts about 25 steps (`saltus_solvers::lagrangian::neighbours`)
    pub skin: f64,
    /// fluid coupling
    pub fluid: FluidMode,
    /// fluid velocity of the drag: `"centre"` (Maurin 2015 eq 11) or `"sphere_average"`
    /// (over the grain's slices, with the exact implicit exchange)
    #[serde(skip_serializing_if = "DragVelocity::is_centre")]
    pub drag_velocity: DragVelocity,
    /// fluid resolution period tau_f (s)
    pub fluid_period: f64,
    /// volume fraction of the fluid's coupling: `"step"` (the slice volumes at the update)
    /// or `"fluid_period"` (their mean over the DEM steps of the fluid period, Cheng et al.
    /// eq 14)
    #[serde(skip_serializing_if = "PhiAverage::is_step")]
    pub phi_average: PhiAverage,
    /// diffusion length L_d of the fluid's volume fraction in grain diameters (Cheng et al.
    /// eq 17, D_t = L_d^2 / tau_f over one fluid period, implicit; Cheng: 1); 0: none
    #[serde(skip_serializing_if = "super::tables::is_zero")]
    pub phi_diffusion: f64,
    /// deposition time before the flow starts, fluid at rest (s); default three
    /// free-fall times of the released lattice under the buoyant weight
    #[serde(skip_serializing_if = "Option::is_none")]
    pub settle_time: Option<f64>,
    /// time after which profiles are averaged (s)
    pub stats_start: f64,
    /// average the granular fields (particle stresses split kinetic/contact, heat flux,
    /// dissipations, I, J, mu_eff, coordination) into profiles.csv with the other
    /// profiles; default on with a fluid, off without (then `true` makes a dry run take
    /// its averaging samples every `fluid_period` after `stats_start`)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub granular_fields: Option<bool>,
    /// averaging window of the steady-state test (s)
    pub steady_window: f64,
    /// steady when the window-averaged transport rate changes by less than this
    /// fraction between consecutive windows
    pub steady_tolerance: f64,
    /// consecutive windows under the tolerance
    pub steady_windows: usize,
    /// stop as soon as the run is steady
    pub stop_when_steady: bool,
    /// stop when the relative standard error of the transport rate over the averaging
    /// window that MSER-5 finds falls to this (a fraction in (0, 1]), or at end_time
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_error: Option<f64>,
    /// threads (0: all cores)
    pub threads: usize,
    /// period of VTK particle snapshots (s); 0: none
    pub vtk_period: f64,
    /// cap on DEM steps
    pub max_steps: u64,
    /// closure tables that replace the scene's `[closures.<family>]`, family by family,
    /// when the DEM runs (the DEM face of a closure whose coupling differs between the
    /// solvers: a fluid-phase viscosity that already holds the grains' share of the
    /// stress the DEM's drag exchange carries)
    #[serde(skip_serializing_if = "toml::Table::is_empty")]
    pub closures: toml::Table,
}

impl Default for LagrangianSettings {
    fn default() -> Self {
        Self {
            end_time: 10.0,
            length: None,
            width: None,
            side_walls: false,
            bottom: Bottom::Rough,
            height: 0.0,
            initial: Initial::Bed,
            particles: None,
            size_dispersion: 0.0,
            rough_layer: 1.0,
            cells: None,
            surface: Surface::Deposit,
            gas_phi: 0.0,
            gas_temperature: 0.0,
            particle_list: Vec::new(),
            dt_safety: 0.05,
            skin: 0.1,
            fluid: FluidMode::Coupled,
            drag_velocity: DragVelocity::Centre,
            fluid_period: 1.0e-2,
            phi_average: PhiAverage::Step,
            phi_diffusion: 0.0,
            settle_time: None,
            stats_start: 0.0,
            granular_fields: None,
            steady_window: 1.0,
            steady_tolerance: 0.05,
            steady_windows: 3,
            stop_when_steady: false,
            target_error: None,
            threads: 0,
            vtk_period: 0.0,
            max_steps: 1_000_000_000_000,
            closures: toml::Table::new(),
        }
    }
}

/// What the derived defaults of the DEM depend on.
pub struct Case {
    /// grain diameter (m)
    pub d: f64,
    /// grain density (kg/m^3)
    pub rho_p: f64,
    /// fluid density (kg/m^3)
    pub rho_f: f64,
    /// gravity (m/s^2)
    pub gravity: f64,
    /// bed height at rest (m)
    pub bed_height: f64,
    /// water depth (m)
    pub water_depth: f64,
    /// packing of the bed
    pub bed_phi: f64,
}

impl LagrangianSettings {
    /// Fill the derived defaults. A default that cannot be derived stays `None`.
    pub fn resolve(&mut self, c: &Case) {
        self.length.get_or_insert(CELL_DIAMETERS * c.d);
        self.width.get_or_insert(CELL_DIAMETERS * c.d);
        if self.cells.is_none() {
            let h = c.bed_height + c.water_depth;
            let n = ((h * FLUID_CELLS_PER_DIAMETER / c.d).round() as usize).max(2);
            // a default over the cap is left out (so that the resolved scene passes the
            // check of a given count), refused by `check_active` only if the DEM runs
            self.cells = (n <= MAX_FLUID_CELLS).then_some(n);
        }
        self.granular_fields.get_or_insert(self.fluid != FluidMode::Off);
        if self.settle_time.is_none() {
            // the lattice holds the mobile bed, the two diameters removed under it and
            // the rough layer, at the loose packing of the lattice
            let solid = (c.bed_height + (self.rough_layer + 2.0) * c.d) * c.bed_phi;
            let release = solid / LATTICE_PHI;
            let rho_f = if self.fluid == FluidMode::Off { 0.0 } else { c.rho_f };
            let g_buoyant = c.gravity.abs() * (1.0 - rho_f / c.rho_p);
            let t = SETTLE_FALLS * (2.0 * release / g_buoyant).sqrt();
            // round to a millisecond so that the resolved scene reads cleanly; a default
            // beyond the range of the key is left out, as one that cannot be derived
            self.settle_time = (t.is_finite() && t > 0.0 && t <= MAX_TIME).then(|| (t * 1e3).round() / 1e3);
        }
    }

    /// Whether the run averages profiles: with a fluid (at every fluid update), or dry
    /// when it asks for the granular fields.
    pub fn takes_samples(&self) -> bool {
        self.fluid != FluidMode::Off || self.granular_fields == Some(true)
    }

    /// Ranges of the keys given (or derived), whichever solver is active.
    pub(super) fn check(&self, f: &Path, d: f64) -> Result<()> {
        let p = |k: &str| format!("solver.lagrangian.{k}");
        let cut = d * (1.0 + self.skin);
        let side = ParamRange::closed(d, MAX_SIDE_DIAMETERS * d);
        check(f, &p("end_time"), self.end_time, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("skin"), self.skin, ParamRange::open_closed(0.0, 2.0))?;
        if let Some(l) = self.length {
            // minimum image: a particle must not meet two images of another
            check(f, &p("length"), l, ParamRange::open_closed(2.0 * cut, MAX_SIDE_DIAMETERS * d))?;
        }
        if let Some(w) = self.width {
            let range = if self.side_walls { side } else { ParamRange::open_closed(2.0 * cut, MAX_SIDE_DIAMETERS * d) };
            check(f, &p("width"), w, range)?;
        }
        check(f, &p("height"), self.height, ParamRange::closed(0.0, MAX_SIDE_DIAMETERS * d))?;
        check(f, &p("rough_layer"), self.rough_layer, ParamRange::closed(0.5, 10.0))?;
        // the largest grain must fit the released lattice's spacing of 1.1 d
        check(f, &p("size_dispersion"), self.size_dispersion, ParamRange::closed(0.0, MAX_SIZE_DISPERSION))?;
        if let Some(n) = self.cells {
            check(f, &p("cells"), n as f64, ParamRange::closed(2.0, MAX_FLUID_CELLS as f64))?;
        }
        if let Some(n) = self.particles {
            check(f, &p("particles"), n as f64, ParamRange::closed(1.0, MAX_PARTICLES))?;
        }
        check(f, &p("gas_phi"), self.gas_phi, ParamRange::closed_open(0.0, 0.5))?;
        check(f, &p("gas_temperature"), self.gas_temperature, ParamRange::closed(0.0, 1e6))?;
        check(f, &p("dt_safety"), self.dt_safety, ParamRange::open_closed(0.0, 0.3))?;
        check(f, &p("fluid_period"), self.fluid_period, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("phi_diffusion"), self.phi_diffusion, ParamRange::closed(0.0, MAX_PHI_DIFFUSION))?;
        if let Some(t) = self.settle_time {
            check(f, &p("settle_time"), t, ParamRange::closed(0.0, MAX_TIME))?;
        }
        check(f, &p("stats_start"), self.stats_start, ParamRange::closed(0.0, MAX_TIME))?;
        check(f, &p("steady_window"), self.steady_window, ParamRange::open_closed(0.0, MAX_TIME))?;
        check(f, &p("steady_tolerance"), self.steady_tolerance, ParamRange::closed(0.0, 1e6))?;
        check(f, &p("steady_windows"), self.steady_windows as f64, ParamRange::closed(1.0, 1e9))?;
        if let Some(e) = self.target_error {
            check(f, &p("target_error"), e, ParamRange::open_closed(0.0, 1.0))?;
            if self.fluid == FluidMode::Off {
                return Err(key_error(
                    f,
                    &p("target_error"),
                    "the error is that of the transport rate, which a run without fluid does not measure",
                ));
            }
        }
        check(f, &p("threads"), self.threads as f64, ParamRange::closed(0.0, 1024.0))?;
        check(f, &p("vtk_period"), self.vtk_period, ParamRange::closed(0.0, MAX_TIME))?;
        check(f, &p("max_steps"), self.max_steps as f64, ParamRange::closed(1.0, 1e15))?;
        for (k, s) in self.particle_list.iter().enumerate() {
            if s.position.iter().chain(&s.velocity).chain(&s.angular_velocity).any(|v| !v.is_finite() || v.abs() > 1e6)
            {
                return Err(key_error(f, &format!("{}[{k}]", p("particle")), "values must be finite, |x| <= 1e6"));
            }
        }
        Ok(())
    }

    /// What the DEM needs to run, checked when it is the active solver: derived keys
    /// present, the start the `initial` mode needs, a fluid column, a bounded count.
    pub(super) fn check_active(&self, f: &Path, c: &Case) -> Result<()> {
        let p = |k: &str| format!("solver.lagrangian.{k}");
        let need = |k: &str, what: &str| key_error(f, &p(k), format!("missing, and {what}; give it"));
        let length = self.length.ok_or_else(|| need("length", "no default"))?;
        let width = self.width.ok_or_else(|| need("width", "no default"))?;
        if self.initial == Initial::Bed && self.settle_time.is_none() {
            return Err(need(
                "settle_time",
                &format!("the default needs grains heavier than the fluid under gravity, and at most {MAX_TIME:e} s"),
            ));
        }
        if self.cells.is_none() {
            return Err(need(
                "cells",
                &format!(
                    "cells of d/{FLUID_CELLS_PER_DIAMETER} over bed_height + water_depth = {} m are more than {MAX_FLUID_CELLS}",
                    crate::param::number(c.bed_height + c.water_depth)
                ),
            ));
        }
        if self.takes_samples() && self.end_time <= self.stats_start {
            // the averages would hold no sample: refused before the work rather than
            // reported as all-zero profiles after it
            return Err(key_error(
                f,
                &p("stats_start"),
                format!(
                    "{} s is not before solver.lagrangian.end_time = {} s, so the run would average nothing; lower it or raise the end time",
                    crate::param::number(self.stats_start),
                    crate::param::number(self.end_time)
                ),
            ));
        }
        let cut = c.d * (1.0 + self.skin);
        if self.bottom == Bottom::Periodic {
            check(f, &p("height"), self.height, ParamRange::open_closed(2.0 * cut, MAX_SIDE_DIAMETERS * c.d))?;
            if self.fluid == FluidMode::Coupled {
                return Err(key_error(
                    f,
                    &p("fluid"),
                    "a z-periodic box has no fluid column; use fluid = \"off\" or \"still\"",
                ));
            }
        }
        if self.size_dispersion > 0.0 && self.initial != Initial::Bed {
            return Err(key_error(
                f,
                &p("size_dispersion"),
                "draws the diameters of a deposited bed only; use initial = \"bed\" or size_dispersion = 0",
            ));
        }
        let volume = crate::grain::sphere_volume(c.d);
        let count = |height: f64, phi: f64| phi * length * width * height / volume;
        let mobile = match self.initial {
            Initial::Bed => {
                if self.particles.is_none() && c.bed_height <= 0.0 {
                    return Err(key_error(
                        f,
                        "domain.bed_height",
                        "initial = \"bed\" needs bed_height > 0 (m) or solver.lagrangian.particles = N",
                    ));
                }
                if matches!(self.bottom, Bottom::None | Bottom::Periodic) {
                    return Err(key_error(
                        f,
                        &p("bottom"),
                        "a deposited bed needs bottom = \"rough\", \"wall\", \"bead_row\" or \"half_cylinders\"",
                    ));
                }
                self.particles.map_or(count(c.bed_height + (self.rough_layer + 2.0) * c.d, c.bed_phi), |n| n as f64)
            }
            Initial::Gas => {
                if self.bottom.is_frey() {
                    // the gas lattice fills the box from z = 0, through the fixed elements
                    return Err(key_error(
                        f,
                        &p("bottom"),
                        "a gas fills the box from z = 0; use bottom = \"wall\", \"none\" or \"periodic\" with initial = \"gas\"",
                    ));
                }
                check(f, &p("gas_phi"), self.gas_phi, ParamRange::open(0.0, 0.5))?;
                check(f, &p("gas_temperature"), self.gas_temperature, ParamRange::positive())?;
                check(f, &p("height"), self.height, ParamRange::open_closed(2.0 * cut, MAX_SIDE_DIAMETERS * c.d))?;
                self.particles.map_or(count(self.height, self.gas_phi), |n| n as f64)
            }
            Initial::List => {
                if self.particle_list.is_empty() {
                    return Err(key_error(
                        f,
                        &p("particle"),
                        "initial = \"list\" needs [[solver.lagrangian.particle]] entries",
                    ));
                }
                if let Some(k) = self.particle_list.windows(2).position(|w| w[0].fixed && !w[1].fixed) {
                    return Err(key_error(
                        f,
                        &format!("{}[{}]", p("particle"), k + 1),
                        "list mobile particles before fixed ones",
                    ));
                }
                self.particle_list.len() as f64
            }
        };
        if mobile.is_nan() || mobile > MAX_PARTICLES {
            return Err(key_error(
                f,
                &p("length"),
                format!("the box holds {mobile:.3e} particles, more than {MAX_PARTICLES:e}: shrink length, width or the bed"),
            ));
        }
        // a column thinner than a grain resolves nothing, and one of 1e-308 m has cells
        // that underflow: its momentum system is singular at the first fluid update
        if self.fluid != FluidMode::Off && self.bottom != Bottom::Periodic && c.bed_height + c.water_depth < c.d {
            return Err(key_error(
                f,
                "domain.water_depth",
                format!(
                    "the fluid column height bed_height + water_depth = {} m must be at least one grain diameter ({} m)",
                    crate::param::number(c.bed_height + c.water_depth),
                    crate::param::number(c.d)
                ),
            ));
        }
        Ok(())
    }
}
