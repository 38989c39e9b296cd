//! `sweep.json`: what a sweep is (its file, axes and the hash of every point's resolved
//! scene) and how far it is (each point's status, wall and CPU time), rewritten after
//! every point so that an interrupted sweep knows what is finished.

use std::hash::Hasher;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};

use super::spec::{Axis, Combine, Sweep};

/// File name of the manifest in the sweep's folder.
pub const FILE: &str = "sweep.json";

/// Where a point is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// not run yet
    #[default]
    Pending,
    /// running (a manifest left with it was killed hard)
    Running,
    /// ended steady, at its end time or at its step cap
    Done,
    /// stopped unstable; its last good state is written
    Unstable,
    /// interrupted; its state so far is written (with a DEM checkpoint)
    Interrupted,
    /// could not be set up or its outputs not written
    Failed,
}

impl Status {
    /// Whether `--resume` keeps the point as it is: a finished run (an unstable one
    /// would break down again at the same step).
    pub fn finished(self) -> bool {
        matches!(self, Status::Done | Status::Unstable)
    }
}

/// One point in the manifest.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct PointEntry {
    /// position in the sweep
    pub index: usize,
    /// output folder, relative to the sweep's folder
    pub dir: String,
    /// per axis name, the value (as in the sweep file)
    pub values: toml::Table,
    /// FNV-1a 64 of the point's resolved scene (hex)
    pub scene_hash: String,
    /// where it is
    pub status: Status,
    /// how the run ended (`summary.json`'s ending)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ending: Option<String>,
    /// wall-clock time of the run (s), summed over its continuations (`--resume`)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_time_s: Option<f64>,
    /// CPU time of the run (s): its summary's `cpu_time_s` (the driving thread and the
    /// solver's own pool), else the driving thread's; summed over its continuations
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_time_s: Option<f64>,
    /// folder of the point whose state this one started from (a warm start)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warm_start_from: Option<String>,
    /// why the point started from rest although its parent ended done (a warm start its
    /// scene cannot take)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warm_start_refused: Option<String>,
    /// why it failed or stopped early
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The whole manifest.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Manifest {
    /// the sweep file, as given
    pub sweep: PathBuf,
    /// its name
    pub name: String,
    /// FNV-1a 64 over the points' scene hashes (hex): what `--resume` compares
    pub sweep_hash: String,
    /// product or zip
    pub combine: Combine,
    /// the axes
    pub axes: Vec<AxisEntry>,
    /// the points
    pub points: Vec<PointEntry>,
}

/// An axis in the manifest.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct AxisEntry {
    /// scene key
    pub key: String,
    /// column name
    pub name: String,
    /// values
    pub values: Vec<toml::Value>,
    /// labels
    pub labels: Vec<String>,
}

impl From<&Axis> for AxisEntry {
    fn from(a: &Axis) -> Self {
        Self { key: a.key.clone(), name: a.name.clone(), values: a.values.clone(), labels: a.labels.clone() }
    }
}

/// FNV-1a 64 of `bytes`, as 16 hex digits.
pub fn hash(bytes: &[u8]) -> String {
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    format!("{:016x}", h.finish())
}

impl Manifest {
    /// A fresh manifest of `sweep` whose points' resolved scenes hash to `hashes`.
    pub fn new(sweep: &Sweep, hashes: Vec<String>) -> Self {
        let sweep_hash = hash(hashes.join("\n").as_bytes());
        let points = sweep
            .points
            .iter()
            .zip(hashes)
            .map(|(p, h)| PointEntry {
                index: p.index,
                dir: p.dir_name(),
                values: sweep.axes.iter().zip(&p.at).map(|(a, &k)| (a.name.clone(), a.values[k].clone())).collect(),
                scene_hash: h,
                ..PointEntry::default()
            })
            .collect();
        Self {
            sweep: sweep.file.clone(),
            name: sweep.meta.name.clone(),
            sweep_hash,
            combine: sweep.combine,
            axes: sweep.axes.iter().map(AxisEntry::from).collect(),
            points,
        }
    }

    /// Read `dir/sweep.json`.
    pub fn read(dir: &Path) -> anyhow::Result<Self> {
        let f = dir.join(FILE);
        let text = std::fs::read_to_string(&f).with_context(|| format!("{}: cannot read", f.display()))?;
        serde_json::from_str(&text).with_context(|| format!("{}: not a sweep manifest", f.display()))
    }

    /// Write `dir/sweep.json` whole (through a temporary file, so that an interrupt never
    /// leaves half a manifest).
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        let f = dir.join(FILE);
        let tmp = dir.join(format!("{FILE}.tmp"));
        let text = serde_json::to_string_pretty(self)? + "\n";
        std::fs::write(&tmp, text).with_context(|| format!("{}: cannot write", tmp.display()))?;
        std::fs::rename(&tmp, &f).with_context(|| format!("{}: cannot write", f.display()))
    }
}
