//! The physical tables of a scene: `[meta]`, `[fluid]`, `[particles]` (with
//! `[particles.contact]`), `[physics]`, `[output]` and `[reference]`.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::check;
use crate::error::Result;
use crate::param::ParamRange;

/// Free-form description.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Meta {
    /// short name, used for output folders
    #[serde(default)]
    pub name: String,
    /// one paragraph
    #[serde(default)]
    pub description: String,
    /// the closures file (`saltus run --closures FILE`) whose tables replaced the scene's,
    /// absolute: a record of where the `[closures]` tables came from, not read again
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closures_file: Option<String>,
}

/// Carrier fluid.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// density rho_f (kg/m^3)
    #[serde(default = "default_rho_f")]
    pub density: f64,
    /// kinematic viscosity nu_f (m^2/s)
    #[serde(default = "default_nu_f")]
    pub viscosity: f64,
}

fn default_rho_f() -> f64 {
    1000.0
}
fn default_nu_f() -> f64 {
    1.0e-6
}

impl Default for Fluid {
    fn default() -> Self {
        Self { density: default_rho_f(), viscosity: default_nu_f() }
    }
}

/// Which contact law the DEM integrates.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ContactModel {
    /// linear spring-dashpot + Coulomb slider
    #[default]
    Linear,
    /// Hertz-Mindlin with restitution-matched damping
    Hertz,
}

/// Whether the normal force of a contact may pull: the dashpot of a spring-dashpot law
/// turns attractive as the grains separate (the overlap still positive, the normal
/// velocity large); a repulsive law ends the contact where the total force reaches zero.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum NormalForce {
    /// k_n delta - c_n v_n as it is, attractive at the end of a collision; the linear
    /// law's restitution is exactly e = exp(-pi zeta / sqrt(1 - zeta^2))
    #[default]
    SpringDashpot,
    /// max(k_n delta - c_n v_n, 0), as the DEM code of Maurin et al. 2015 and Chassagne
    /// et al. 2023 computes it; the linear law's damping is then matched to e by Schwager
    /// & Poschel 2007's restitution of that force, e = exp(-r (pi - 2 arctan r)) with
    /// r = zeta / sqrt(1 - zeta^2), which reaches e^-2 at critical damping: e must be
    /// above e^-2 = 0.1353
    Repulsive,
}

/// How the tangential spring of a contact (its history xi) follows the contact frame as
/// the pair rolls and spins.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum TangentialHistory {
    /// projected on the new tangent plane every step, xi - (xi . n) n: the spring
    /// shortens by a factor cos(angle the normal turned), second order in the step, and
    /// does not turn with the pair's spin about the normal
    #[default]
    Project,
    /// turned with the contact: rotated onto the new tangent plane with its length kept,
    /// then about the normal by the pair's mean spin about it, 0.5 (w_i + w_j) . n dt
    /// (the objective update of YADE's `ScGeom::rotate`, described in the DEM formulation
    /// chapter of Smilauer et al. 2015, the code the DEM of Maurin 2015 and Chassagne 2023
    /// runs)
    Rotate,
}

/// `[particles.contact]`: the contact law of the grains and its parameters.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// the law
    #[serde(default)]
    pub law: ContactModel,
    /// normal stiffness k_n of the linear law (N/m); default: the rigid limit of the case
    /// (see [`Particles::rigid_stiffness`]), resolved at load
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// k_t / k_n of the linear law
    #[serde(default = "default_tangential_ratio")]
    pub tangential_ratio: f64,
    /// Young modulus of the Hertz law (Pa)
    #[serde(default = "default_young")]
    pub young: f64,
    /// Poisson ratio of the Hertz law
    #[serde(default = "default_poisson")]
    pub poisson: f64,
    /// whether the normal force may pull (see [`NormalForce`])
    #[serde(default)]
    pub normal_force: NormalForce,
    /// how the tangential spring follows the contact (see [`TangentialHistory`])
    #[serde(default)]
    pub tangential_history: TangentialHistory,
}

fn default_tangential_ratio() -> f64 {
    1.0
}
fn default_young() -> f64 {
    1.0e7
}
fn default_poisson() -> f64 {
    0.3
}

impl Default for Contact {
    fn default() -> Self {
        Self {
            law: ContactModel::Linear,
            stiffness: None,
            tangential_ratio: default_tangential_ratio(),
            young: default_young(),
            poisson: default_poisson(),
            normal_force: NormalForce::SpringDashpot,
            tangential_history: TangentialHistory::Project,
        }
    }
}

/// Grains (monodisperse spheres): what both solvers need, stated once.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Particles {
    /// diameter d (m)
    pub diameter: f64,
    /// density rho_p (kg/m^3)
    pub density: f64,
    /// normal restitution coefficient e; the default is the glass beads of Chassagne et
    /// al. 2023. A kinetic-theory closure takes it unless it sets its own.
    #[serde(default = "default_restitution")]
    pub restitution: f64,
    /// interparticle friction coefficient mu_p (same default and inheritance)
    #[serde(default = "default_friction")]
    pub friction: f64,
    /// friction coefficient of the particles on the flat walls (DEM side walls and flat
    /// bottom); default the interparticle friction (Maurin's YADE script of the Frey
    /// runs gives the walls the beads' material, friction 0.4)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_friction: Option<f64>,
    /// contact law (DEM)
    #[serde(default)]
    pub contact: Contact,
}

fn default_restitution() -> f64 {
    0.7
}
fn default_friction() -> f64 {
    0.4
}

/// Largest overlap over d under the weight of the bed that still counts as rigid: the
/// inverse of the stiffness number k_n / (P d) = 2500 (da Cruz et al. 2005 call 1e3 to 1e4
/// the rigid limit). With rounding up to one significant figure it gives the validated
/// k_n = 1e4 N/m of Chassagne 2023 case 1 (9.9e3 before rounding).
const RIGID_OVERLAP: f64 = 4.0e-4;

/// Range of `particles.contact.stiffness` (N/m).
pub(super) const STIFFNESS: ParamRange = ParamRange::closed(1e-6, 1e12);

impl Particles {
    /// The properties a granular closure inherits ([`crate::GranularStress::inherit`]).
    pub fn grains(&self) -> crate::Grains {
        crate::Grains {
            diameter: self.diameter,
            density: self.density,
            restitution: self.restitution,
            friction: self.friction,
        }
    }

    /// Default normal stiffness of the linear law (N/m) in the rigid limit: the weight
    /// of the bed column over one grain, P d^2 with P = (rho_p - rho_f) g phi H (rho_f
    /// = 0 when `dry`; H the bed height, at least 10 d), compresses a contact by
    /// 4e-4 d; rounded up to one significant figure. None when the grains weigh nothing
    /// (no gravity, or grains not denser than the fluid): the stiffness must then be given.
    pub fn rigid_stiffness(&self, rho_f: f64, gravity: f64, bed_phi: f64, bed_height: f64) -> Option<f64> {
        let d = self.diameter;
        let pressure = (self.density - rho_f) * gravity.abs() * bed_phi * bed_height.max(10.0 * d);
        let k = pressure * d / RIGID_OVERLAP;
        (k.is_finite() && k > 0.0).then(|| round_up_one_figure(k))
    }

    pub(super) fn check(&self, f: &Path) -> Result<()> {
        check(f, "particles.diameter", self.diameter, ParamRange::closed(1e-7, 1.0))?;
        check(f, "particles.density", self.density, ParamRange::closed(1e-3, 1e5))?;
        check(f, "particles.restitution", self.restitution, ParamRange::open_closed(0.0, 1.0))?;
        check(f, "particles.friction", self.friction, ParamRange::closed(0.0, 2.0))?;
        if let Some(mu) = self.wall_friction {
            check(f, "particles.wall_friction", mu, ParamRange::closed(0.0, 2.0))?;
        }
        let c = &self.contact;
        if let Some(k) = c.stiffness {
            check(f, "particles.contact.stiffness", k, STIFFNESS)?;
        }
        check(f, "particles.contact.tangential_ratio", c.tangential_ratio, ParamRange::closed(0.0, 10.0))?;
        check(f, "particles.contact.young", c.young, ParamRange::closed(1.0, 1e13))?;
        check(f, "particles.contact.poisson", c.poisson, ParamRange::closed(0.0, 0.5))?;
        if c.normal_force == NormalForce::Repulsive && c.law == ContactModel::Linear {
            // the underdamped repulsive law cannot dissipate more (an overdamped one is
            // not implemented)
            let range = ParamRange::open_closed((-2.0f64).exp(), 1.0);
            if !range.contains(self.restitution) {
                return Err(crate::error::Error::OutOfRange {
                    file: f.into(),
                    key: "particles.restitution".into(),
                    value: crate::param::number(self.restitution),
                    allowed: format!(
                        "{range} with particles.contact.normal_force = \"repulsive\" (e^-2 at critical damping)"
                    ),
                });
            }
        }
        Ok(())
    }
}

fn round_up_one_figure(x: f64) -> f64 {
    let scale = 10f64.powf(x.log10().floor());
    (x / scale).ceil() * scale
}

/// Body forces.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Physics {
    /// gravity (m/s^2)
    #[serde(default = "default_g")]
    pub gravity: f64,
    /// bed slope sin(alpha)
    #[serde(default)]
    pub slope: f64,
    /// imposed streamwise pressure gradient -dp/dx (Pa/m)
    #[serde(default)]
    pub pressure_gradient: f64,
    /// Shields number the scene is driven at; the loader sets the quantity `drive` names
    /// from it ([`super::shields`])
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shields: Option<f64>,
    /// what `shields` sets: the water depth, the slope or the pressure gradient
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive: Option<Drive>,
    /// the weight `shields` is measured against: the bed-normal one (the default) or the
    /// vertical one
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shields_weight: Option<ShieldsWeight>,
    /// a driving that varies in time, added to `pressure_gradient` (`[physics.forcing]`,
    /// read on its own by [`super::Forcing::from_value`])
    #[serde(skip_deserializing, skip_serializing_if = "Option::is_none")]
    pub forcing: Option<super::Forcing>,
}

/// The quantity a scene's Shields number (`physics.shields`) sets.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Drive {
    /// `domain.water_depth`, under the scene's slope or pressure gradient
    WaterDepth,
    /// `physics.slope` (sin alpha), over the scene's water depth
    Slope,
    /// `physics.pressure_gradient`, over the scene's water depth
    PressureGradient,
}

impl Drive {
    /// The scene key it sets.
    pub fn key(self) -> &'static str {
        match self {
            Drive::WaterDepth => "domain.water_depth",
            Drive::Slope => "physics.slope",
            Drive::PressureGradient => "physics.pressure_gradient",
        }
    }
}

/// The submerged weight a Shields number divides the bed shear stress by.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ShieldsWeight {
    /// (rho_p - rho_f) g cos(alpha) d, the bed-normal weight (Maurin et al. 2015, and the
    /// summary's `shields_nominal`)
    #[default]
    BedNormal,
    /// (rho_p - rho_f) g d, the vertical weight (Chassagne et al. 2023, section 3.1)
    Vertical,
}

fn default_g() -> f64 {
    crate::G
}

impl Default for Physics {
    fn default() -> Self {
        Self {
            gravity: crate::G,
            slope: 0.0,
            pressure_gradient: 0.0,
            shields: None,
            drive: None,
            shields_weight: None,
            forcing: None,
        }
    }
}

/// Output settings.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// output folder; `out/<meta.name>` when absent
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir: Option<String>,
    /// simulated time between two rows of `timeseries.csv` (s); default: the active
    /// solver's end time / [`TIMESERIES_ROWS`], resolved at load
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timeseries_interval: Option<f64>,
    /// simulated time between two profile snapshots (s); 0 (the default) writes none
    #[serde(default)]
    pub snapshot_interval: f64,
    /// simulated time between two checkpoints of a DEM run (s); 0 (the default) writes
    /// one only when the run stops (interrupted or at its end)
    #[serde(default)]
    pub checkpoint_interval: f64,
    /// phase bins of the phase averages of a periodic `physics.forcing` (`phases.csv`,
    /// `phase_profiles.csv`); 0 (the default) computes none
    #[serde(default, skip_serializing_if = "is_zero_usize")]
    pub phases: usize,
    /// whole periods of the forcing left out of the phase averages, from the start
    #[serde(default = "default_spin_up", skip_serializing_if = "is_default_spin_up")]
    pub spin_up_periods: usize,
}

fn is_zero_usize(n: &usize) -> bool {
    *n == 0
}
fn default_spin_up() -> usize {
    1
}
fn is_default_spin_up(n: &usize) -> bool {
    *n == default_spin_up()
}

impl Default for Output {
    fn default() -> Self {
        Self {
            dir: None,
            timeseries_interval: None,
            snapshot_interval: 0.0,
            checkpoint_interval: 0.0,
            phases: 0,
            spin_up_periods: default_spin_up(),
        }
    }
}

/// Most phase bins of `output.phases`.
pub const MAX_PHASES: usize = 10_000;

/// Rows of `timeseries.csv` over the end time with the default interval.
pub const TIMESERIES_ROWS: f64 = 1000.0;
/// Most rows `output.timeseries_interval` may ask for over the end time.
pub const MAX_TIMESERIES_ROWS: f64 = 1.0e7;
/// Most snapshots or checkpoints `output.snapshot_interval` and
/// `output.checkpoint_interval` may ask for over the end time.
pub const MAX_SNAPSHOTS: f64 = 1.0e5;

impl Output {
    /// Fill the default interval of the time series for a run of `end_time` seconds.
    pub(super) fn resolve(&mut self, end_time: f64) {
        if self.timeseries_interval.is_none() {
            self.timeseries_interval = Some(end_time / TIMESERIES_ROWS);
        }
    }

    /// The intervals against the active solver's `end_time` (s), named by `end_key`: each
    /// is a time, and none asks for more rows or files than a run can hold.
    pub(super) fn check(&self, f: &Path, end_time: f64, end_key: &str) -> Result<()> {
        if self.dir.as_deref().is_some_and(|d| d.trim().is_empty()) {
            return Err(crate::error::Error::Key {
                file: f.into(),
                key: "output.dir".into(),
                message: "an empty path; give a folder, or leave the key out for out/<meta.name>".into(),
            });
        }
        let max = super::MAX_TIME;
        check(f, "output.phases", self.phases as f64, ParamRange::closed(0.0, MAX_PHASES as f64))?;
        check(f, "output.spin_up_periods", self.spin_up_periods as f64, ParamRange::closed(0.0, 1e6))?;
        if let Some(t) = self.timeseries_interval {
            check(f, "output.timeseries_interval", t, ParamRange::open_closed(0.0, max))?;
            at_least(f, "output.timeseries_interval", t, end_time, end_key, MAX_TIMESERIES_ROWS, "rows")?;
        }
        for (key, t) in [
            ("output.snapshot_interval", self.snapshot_interval),
            ("output.checkpoint_interval", self.checkpoint_interval),
        ] {
            check(f, key, t, ParamRange::closed(0.0, max))?;
            if t > 0.0 {
                at_least(f, key, t, end_time, end_key, MAX_SNAPSHOTS, "files")?;
            }
        }
        Ok(())
    }
}

/// Refuse an interval `t` at `key` that asks for more than `most` rows or files over
/// `end_time`.
fn at_least(f: &Path, key: &str, t: f64, end_time: f64, end_key: &str, most: f64, what: &str) -> Result<()> {
    let least = end_time / most;
    if t >= least {
        return Ok(());
    }
    Err(crate::error::Error::OutOfRange {
        file: f.into(),
        key: key.into(),
        value: crate::param::number(t),
        allowed: format!(
            "{}at least {end_key} / {most:e} = {} s: at most {most:e} {what} per run",
            if what == "files" { "0 (off) or " } else { "" },
            crate::param::number(least)
        ),
    })
}

/// Reference data overlaid on the run's plots: `[reference]` for one file, or
/// `[[reference]]` for several (a velocity file and a concentration file, say).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Reference {
    /// whitespace- or comma-separated columns file, relative to the scene file (made
    /// absolute when the scene is loaded, so that a resolved scene works from anywhere)
    pub file: String,
    /// column names of the file, in order
    pub columns: Vec<String>,
    /// added to the file's `z` column (m), for data measured from another origin (from the
    /// bed surface instead of the bottom of the column, say)
    #[serde(default, skip_serializing_if = "is_zero")]
    pub z_offset: f64,
}

pub(super) fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// `[reference]` (one table) or `[[reference]]` (an array of tables), the value of key
/// `reference` of `file`. Each table is read on its own with its full key path
/// (`reference[1].columns`), so that a mistake is reported where it is, not as "no
/// variant matched".
pub(super) fn references(value: Option<toml::Value>, file: &Path) -> Result<Vec<Reference>> {
    match value {
        None => Ok(Vec::new()),
        Some(v @ toml::Value::Table(_)) => Ok(vec![super::de_path(v, file, "reference")?]),
        Some(toml::Value::Array(items)) => {
            items.into_iter().enumerate().map(|(i, v)| super::de_path(v, file, &format!("reference[{i}]"))).collect()
        }
        Some(other) => Err(crate::error::Error::Key {
            file: file.into(),
            key: "reference".into(),
            message: format!(
                "expected a table ([reference]) or an array of tables ([[reference]]), found {}",
                other.type_str()
            ),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_stiffness_of_chassagne_case_1_is_the_validated_1e4() {
        let p = Particles {
            diameter: 6e-3,
            density: 2500.0,
            restitution: 0.7,
            friction: 0.4,
            wall_friction: None,
            contact: Contact::default(),
        };
        // (2500 - 1000) 9.81 0.6 0.075 Pa x 6e-3 m / 4e-4 = 9.93e3, rounded up
        assert_eq!(p.rigid_stiffness(1000.0, 9.81, 0.6, 0.075), Some(1.0e4));
        assert_eq!(p.rigid_stiffness(1000.0, 0.0, 0.6, 0.075), None);
        assert_eq!(round_up_one_figure(0.0123), 0.02);
    }
}
