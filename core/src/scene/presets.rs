//! `accuracy = "draft" | "standard" | "fine"`: named sets of the numerical defaults of
//! both solvers, chosen from the work-precision fronts of docs/performance.md.
//!
//! A preset only changes defaults: a key the scene (or `--set`) gives keeps its value.
//! `"standard"` is the defaults themselves, so a scene without `accuracy` and one with
//! `accuracy = "standard"` resolve to the same numbers. The keys a preset sets:
//!
//! | key | draft | standard | fine |
//! |---|---|---|---|
//! | `domain.cells` (Eulerian) | half the default (cells of d/2) | cells of d/4 | twice (d/8) |
//! | `solver.eulerian.steady_tolerance` | 1e-4 | 1e-6 | 1e-6 |
//! | `solver.lagrangian.dt_safety` | 0.22 | 0.05 | 0.05 |
//! | `solver.lagrangian.cells` (fluid) | cells of d/10 | d/30 | d/30 |
//! | `solver.lagrangian.end_time` | 10 s | 10 s | 20 s |
//! | `solver.lagrangian.stats_start` | 0 | 0 | half the end time |
//!
//! The cell counts follow the column's height as the defaults do; a `domain.cell_size`
//! sets both counts and the preset then sets neither.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::domain::{Domain, CELLS_PER_DIAMETER};
use super::lagrangian::{LagrangianSettings, FLUID_CELLS_PER_DIAMETER, MAX_FLUID_CELLS};
use super::solver::EulerianSettings;
use crate::error::{Error, Result};

/// The scene key that chooses a preset.
pub const KEY: &str = "accuracy";

/// The presets, in the order of their cost.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Accuracy {
    /// about a third of the standard cost: errors within the seed scatter of the DEM, a
    /// few per cent in the two-fluid model
    Draft,
    /// the defaults
    #[default]
    Standard,
    /// the two-fluid grid doubled; the DEM run twice as long, its second half averaged
    Fine,
}

/// What a preset sets; see the module's table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Eulerian cells over the default count (cells of d/4)
    pub cells_factor: f64,
    /// `solver.eulerian.steady_tolerance`
    pub steady_tolerance: f64,
    /// `solver.lagrangian.dt_safety`
    pub dt_safety: f64,
    /// fluid cells of the DEM per grain diameter
    pub fluid_cells_per_diameter: f64,
    /// `solver.lagrangian.end_time` (s)
    pub end_time: f64,
    /// `solver.lagrangian.stats_start` over the DEM's end time
    pub stats_start_fraction: f64,
}

/// The names a scene may give, in the order of [`Accuracy::ALL`].
pub const NAMES: [&str; 3] = ["draft", "standard", "fine"];

impl Accuracy {
    /// Every preset, cheapest first.
    pub const ALL: [Accuracy; 3] = [Accuracy::Draft, Accuracy::Standard, Accuracy::Fine];

    /// The name a scene gives.
    pub fn name(self) -> &'static str {
        match self {
            Accuracy::Draft => NAMES[0],
            Accuracy::Standard => NAMES[1],
            Accuracy::Fine => NAMES[2],
        }
    }

    /// The values the preset sets.
    pub fn preset(self) -> Preset {
        let standard = Preset {
            cells_factor: 1.0,
            steady_tolerance: EulerianSettings::default().steady_tolerance,
            dt_safety: LagrangianSettings::default().dt_safety,
            fluid_cells_per_diameter: FLUID_CELLS_PER_DIAMETER,
            end_time: LagrangianSettings::default().end_time,
            stats_start_fraction: 0.0,
        };
        match self {
            Accuracy::Standard => standard,
            // the fronts: half the cells moved qs* by 0.1-6 %, a tolerance of 1e-4 by at
            // most 0.4 %; dt_safety 0.22 and fluid cells of d/10 stayed within the DEM's
            // seed scatter (2.1 %) at 28 % of the CPU time of 0.05
            Accuracy::Draft => Preset {
                cells_factor: 0.5,
                steady_tolerance: 1e-4,
                dt_safety: 0.22,
                fluid_cells_per_diameter: 10.0,
                ..standard
            },
            // twice the cells: qs* within 0.6 % of eight times the cells on the bedload
            // fronts; no DEM resolution factor measured below the seed scatter, so the
            // DEM spends its time on statistics: twice the run, the start of the flow left
            // out of the averages
            Accuracy::Fine => Preset { cells_factor: 2.0, end_time: 20.0, stats_start_fraction: 0.5, ..standard },
        }
    }

    /// Take the preset out of a raw scene table: `None` when the scene gives none; a value
    /// that is not a preset's name is refused naming the file, the key and the names.
    pub fn take(table: &mut toml::Table, file: &Path) -> Result<Option<Accuracy>> {
        let Some(value) = table.remove(KEY) else { return Ok(None) };
        let found = match &value {
            toml::Value::String(s) => format!("`{s}`"),
            other => format!("a {}", other.type_str()),
        };
        let name = value.as_str().unwrap_or_default();
        match Accuracy::ALL.into_iter().find(|a| a.name() == name) {
            Some(a) => Ok(Some(a)),
            None => Err(Error::Key {
                file: file.into(),
                key: KEY.into(),
                message: format!("{found} is not a preset; allowed: \"{}\"", NAMES.join("\", \"")),
            }),
        }
    }

    /// Write the preset's solver keys into a raw scene table where the scene gives none,
    /// so that the scene's own keys win. The cell counts depend on the column and are set
    /// at resolution ([`Accuracy::eulerian_cells`], [`Accuracy::fluid_cells`]).
    pub fn apply(self, table: &mut toml::Table) {
        if self == Accuracy::Standard {
            return;
        }
        let p = self.preset();
        let mut solver = subtable(table, "solver");
        if let Some(e) = solver.as_deref_mut().and_then(|s| subtable(s, "eulerian")) {
            e.entry("steady_tolerance").or_insert(toml::Value::Float(p.steady_tolerance));
        }
        if let Some(l) = solver.and_then(|s| subtable(s, "lagrangian")) {
            l.entry("dt_safety").or_insert(toml::Value::Float(p.dt_safety));
            let end = l.entry("end_time").or_insert(toml::Value::Float(p.end_time));
            // an end time that is not a number is left to the check of its key
            let end = end.as_float().or_else(|| end.as_integer().map(|i| i as f64));
            if let Some(end) = end.filter(|_| p.stats_start_fraction > 0.0) {
                l.entry("stats_start").or_insert(toml::Value::Float(p.stats_start_fraction * end));
            }
        }
    }

    /// Eulerian cells when the scene gives neither `domain.cells` nor
    /// `domain.cell_size`: the default count scaled by the preset (`None` for the
    /// default itself).
    pub fn eulerian_cells(self, domain: &Domain, d: f64) -> Option<usize> {
        let f = self.preset().cells_factor;
        (f != 1.0).then(|| ((domain.height() * CELLS_PER_DIAMETER * f / d).round() as usize).max(4))
    }

    /// Fluid cells of the DEM when the scene gives none, over the column of `height` m:
    /// `None` for the default (cells of d/30), or when the count would pass the cap (the
    /// default's rule then refuses it if the DEM runs).
    pub fn fluid_cells(self, height: f64, d: f64) -> Option<usize> {
        let per_d = self.preset().fluid_cells_per_diameter;
        if per_d == FLUID_CELLS_PER_DIAMETER {
            return None;
        }
        let n = ((height * per_d / d).round() as usize).max(2);
        (n <= MAX_FLUID_CELLS).then_some(n)
    }
}

/// The table at `key` of `table`, created when absent; `None` when `key` holds something
/// else (refused later by the check of the scene's tables).
fn subtable<'a>(table: &'a mut toml::Table, key: &str) -> Option<&'a mut toml::Table> {
    table.entry(key).or_insert_with(|| toml::Value::Table(toml::Table::new())).as_table_mut()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_is_the_defaults() {
        let p = Accuracy::Standard.preset();
        assert_eq!(p.steady_tolerance, 1e-6);
        assert_eq!(p.dt_safety, 0.05);
        assert_eq!(p.fluid_cells_per_diameter, 30.0);
        assert_eq!(p.end_time, 10.0);
        assert_eq!(p.stats_start_fraction, 0.0);
        let mut t: toml::Table = "seed = 1\n".parse().unwrap();
        Accuracy::Standard.apply(&mut t);
        assert_eq!(t, "seed = 1\n".parse().unwrap());
        assert_eq!(Accuracy::Standard.eulerian_cells(&Domain::default(), 1e-3), None);
        assert_eq!(Accuracy::Standard.fluid_cells(0.1, 1e-3), None);
    }

    #[test]
    fn a_preset_fills_only_the_keys_not_given() {
        let mut t: toml::Table = "[solver.lagrangian]\ndt_safety = 0.1\nend_time = 15\n".parse().unwrap();
        Accuracy::Fine.apply(&mut t);
        let l = &t["solver"]["lagrangian"];
        assert_eq!(l["dt_safety"].as_float(), Some(0.1));
        assert_eq!(l["end_time"].as_integer(), Some(15));
        assert_eq!(l["stats_start"].as_float(), Some(7.5));
        assert_eq!(t["solver"]["eulerian"]["steady_tolerance"].as_float(), Some(1e-6));
        let mut t = toml::Table::new();
        Accuracy::Draft.apply(&mut t);
        assert_eq!(t["solver"]["lagrangian"]["dt_safety"].as_float(), Some(0.22));
        assert!(t["solver"]["lagrangian"].get("stats_start").is_none());
        assert_eq!(t["solver"]["eulerian"]["steady_tolerance"].as_float(), Some(1e-4));
    }

    #[test]
    fn names_round_trip_and_a_bad_one_is_refused_with_the_allowed_names() {
        for a in Accuracy::ALL {
            let mut t = toml::Table::new();
            t.insert(KEY.into(), toml::Value::String(a.name().into()));
            assert_eq!(Accuracy::take(&mut t, Path::new("s.toml")).unwrap(), Some(a));
            assert!(t.is_empty());
        }
        for bad in ["accuracy = \"coarse\"", "accuracy = 2"] {
            let mut t: toml::Table = bad.parse().unwrap();
            let e = Accuracy::take(&mut t, Path::new("s.toml")).unwrap_err().to_string();
            assert!(e.contains("s.toml") && e.contains("`accuracy`"), "{e}");
            assert!(e.contains("\"draft\", \"standard\", \"fine\""), "{e}");
        }
    }
}
