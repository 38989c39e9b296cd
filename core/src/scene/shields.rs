//! `physics.shields` with `physics.drive`: a scene given by its Shields number, the
//! quantity that drives the flow set from it at load.
//!
//! The bed shear stress of a column driven by gravity along a slope sin(alpha) and by a
//! pressure gradient G = -dp/dx over a water depth h_w is the weight of the water above
//! the bed plus the push of the gradient on it,
//!
//!   tau_b = (rho_f g sin(alpha) + G) h_w,
//!
//! and the Shields number is tau_b over the submerged weight of a grain layer,
//! theta = tau_b / ((rho_p - rho_f) g c d) with c = cos(alpha) for the bed-normal weight
//! (Maurin et al. 2015, and the summary's `shields_nominal`) or c = 1 for the vertical
//! weight (Chassagne et al. 2023, section 3.1: theta = rho_f h_w sin(alpha) / ((rho_p -
//! rho_f) d)). Open-channel flow on a slope (G = 0) and the pressure-driven column
//! (alpha = 0, Cheng et al. 2018: u*^2 = G h / rho_f) are its two cases. A Couette
//! column is driven by its lid, not by a Shields number, and is refused.

use std::path::Path;

use super::{Domain, Drive, Fluid, Particles, Physics, ShieldsWeight, Top};
use crate::error::{Error, Result};
use crate::param::{number, ParamRange};

/// Largest Shields number a scene may be driven at: far into sheet flow (Wilson's
/// sheet-flow data reach theta of a few), small enough that the driven depth or
/// gradient stays finite.
pub const MAX_SHIELDS: f64 = 100.0;

/// Which keys the scene file gave (before defaults), so that a driven key given by hand
/// is compared with the value the Shields number sets rather than silently replaced.
#[derive(Clone, Copy, Debug, Default)]
pub struct Given {
    /// `domain.water_depth` is in the file
    pub water_depth: bool,
    /// `physics.slope` is in the file
    pub slope: bool,
    /// `physics.pressure_gradient` is in the file
    pub pressure_gradient: bool,
}

impl Given {
    /// The keys of `table`, a raw scene.
    pub fn of(table: &toml::Table) -> Self {
        let has = |t: &str, k: &str| table.get(t).and_then(|v| v.as_table()).is_some_and(|t| t.contains_key(k));
        Self {
            water_depth: has("domain", "water_depth"),
            slope: has("physics", "slope"),
            pressure_gradient: has("physics", "pressure_gradient"),
        }
    }

    fn of_drive(&self, drive: Drive) -> bool {
        match drive {
            Drive::WaterDepth => self.water_depth,
            Drive::Slope => self.slope,
            Drive::PressureGradient => self.pressure_gradient,
        }
    }
}

/// Set the quantity `physics.drive` names from `physics.shields`, in place; nothing when
/// the scene gives no Shields number. Errors name the file and the key.
pub fn resolve(
    physics: &mut Physics,
    domain: &mut Domain,
    fluid: &Fluid,
    particles: &Particles,
    given: Given,
    f: &Path,
) -> Result<()> {
    let key = |k: &str, m: String| Error::Key { file: f.into(), key: k.into(), message: m };
    let (theta, drive) = match (physics.shields, physics.drive) {
        (None, None) => {
            if physics.shields_weight.is_some() {
                return Err(key(
                    "physics.shields_weight",
                    "only used with physics.shields; give it or remove this key".into(),
                ));
            }
            return Ok(());
        }
        (Some(_), None) => return Err(key(
            "physics.drive",
            "missing; physics.shields needs the quantity it sets: \"water_depth\", \"slope\" or \"pressure_gradient\""
                .into(),
        )),
        (None, Some(_)) => {
            return Err(key(
                "physics.shields",
                "missing; physics.drive says what the Shields number sets, give the number".into(),
            ))
        }
        (Some(t), Some(d)) => (t, d),
    };
    super::check(f, "physics.shields", theta, ParamRange::open_closed(0.0, MAX_SHIELDS))?;
    if domain.top == Top::Lid {
        return Err(key(
            "physics.drive",
            "the lid drives a Couette column (domain.top = \"lid\"), not a Shields number; remove physics.shields and physics.drive, or use a free surface or a symmetry plane".into(),
        ));
    }
    let g = physics.gravity;
    let rho_f = fluid.density;
    let buoyant = particles.density - rho_f;
    if !(buoyant > 0.0 && g > 0.0) {
        return Err(key(
            "physics.shields",
            "a Shields number needs grains heavier than the fluid (particles.density > fluid.density) under gravity (physics.gravity > 0)".into(),
        ));
    }
    let d = particles.diameter;
    let vertical = physics.shields_weight.unwrap_or_default() == ShieldsWeight::Vertical;
    let cos = |s: f64| if vertical { 1.0 } else { (1.0 - s * s).max(0.0).sqrt() };
    let value = match drive {
        Drive::WaterDepth => {
            let push = rho_f * g * physics.slope + physics.pressure_gradient;
            if push.is_nan() || push <= 0.0 {
                return Err(key(
                    "physics.drive",
                    format!(
                        "\"water_depth\" needs a slope or a pressure gradient that pushes the flow downstream (rho_f g sin(alpha) + G > 0); physics.slope = {} and physics.pressure_gradient = {} give {}",
                        number(physics.slope),
                        number(physics.pressure_gradient),
                        number(push)
                    ),
                ));
            }
            theta * buoyant * g * cos(physics.slope) * d / push
        }
        Drive::PressureGradient => {
            let h = depth(domain, f, drive)?;
            theta * buoyant * g * cos(physics.slope) * d / h - rho_f * g * physics.slope
        }
        Drive::Slope => {
            let h = depth(domain, f, drive)?;
            if physics.pressure_gradient != 0.0 {
                return Err(key(
                    "physics.drive",
                    "\"slope\" sets the slope that alone drives the flow, and physics.pressure_gradient is not 0: use drive = \"pressure_gradient\", or remove the gradient".into(),
                ));
            }
            // rho_f h tan(alpha) (or sin(alpha) for the vertical weight) = theta (rho_p - rho_f) d
            let t = theta * buoyant * d / (rho_f * h);
            let sin = if vertical { t } else { t / (1.0 + t * t).sqrt() };
            if sin.is_nan() || sin > 1.0 {
                return Err(key(
                    "physics.shields",
                    format!("{} over a water depth of {} m needs sin(alpha) = {} > 1 (vertical weight); lower it or deepen the water", number(theta), number(h), number(sin)),
                ));
            }
            sin
        }
    };
    if !value.is_finite() {
        return Err(key("physics.shields", format!("sets {} to {}, not a finite number", drive.key(), number(value))));
    }
    let slot = match drive {
        Drive::WaterDepth => &mut domain.water_depth,
        Drive::Slope => &mut physics.slope,
        Drive::PressureGradient => &mut physics.pressure_gradient,
    };
    // a resolved scene read again gives the same number; anything else is a contradiction
    if given.of_drive(drive) && (*slot - value).abs() > 1e-12 * value.abs() {
        return Err(key(
            drive.key(),
            format!(
                "= {}, but physics.shields = {} with physics.drive = \"{}\" sets it to {}; remove one of them",
                number(*slot),
                number(theta),
                drive_name(drive),
                number(value)
            ),
        ));
    }
    *slot = value;
    Ok(())
}

fn drive_name(d: Drive) -> &'static str {
    match d {
        Drive::WaterDepth => "water_depth",
        Drive::Slope => "slope",
        Drive::PressureGradient => "pressure_gradient",
    }
}

fn depth(domain: &Domain, f: &Path, drive: Drive) -> Result<f64> {
    if domain.water_depth > 0.0 {
        Ok(domain.water_depth)
    } else {
        Err(Error::Key {
            file: f.into(),
            key: "domain.water_depth".into(),
            message: format!(
                "physics.drive = \"{}\" sets the driving over the water depth, which is 0: give domain.water_depth",
                drive_name(drive)
            ),
        })
    }
}
