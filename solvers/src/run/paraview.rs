//! ParaView output of a run, written by the driver (see [`super::history::Recorder`]): every
//! [`super::Stepper::paraview_period`] of flow time the stepper's documents
//! ([`super::Stepper::paraview`], VTK XML PolyData) go to `<out>/vtk/NAME_NNNNN.vtp`, and
//! `<out>/vtk/series.pvd` lists them with their simulated times, one `part` per document
//! name. The collection is rewritten after every snapshot, so an interrupted run leaves a
//! readable series; a checkpoint carries the snapshots written, so that a restarted run's
//! collection lists them all.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use saltus_core::Error;
use serde::{Deserialize, Serialize};

/// Folder of the snapshots in the run's output folder.
pub const FOLDER: &str = "vtk";
/// File name of the collection.
pub const COLLECTION: &str = "series.pvd";

/// The snapshots written so far and the flow time of the next one.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// (time, file, part) of every dataset written
    entries: Vec<(f64, String, u8)>,
    /// snapshots written
    count: usize,
    /// flow time of the next snapshot (s)
    pub(crate) next: f64,
}

impl Series {
    /// Snapshots written so far.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether no snapshot was written.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The snapshot of simulated time `time` (s) from `documents` into `dir`, and the
    /// collection rewritten; the next one due a `period` later (the next period boundary
    /// after `time` when behind the clock, never one snapshot per unit to catch up).
    pub fn write(
        &mut self,
        dir: &Path,
        time: f64,
        period: f64,
        documents: Result<Vec<(&'static str, String)>, String>,
    ) -> Result<(), Error> {
        self.next += period;
        if self.next <= time {
            // a restart that switched the snapshots on, or a period shorter than a unit
            self.next += ((time - self.next) / period).floor().min(1e15) * period + period;
        }
        let refuse =
            |why: String| Error::Invalid(format!("{}: snapshot at t = {time:e} s not written: {why}", dir.display()));
        if !time.is_finite() {
            return Err(refuse("the time is not finite".into()));
        }
        let documents = documents.map_err(refuse)?;
        std::fs::create_dir_all(dir).map_err(|source| Error::Io { file: dir.to_path_buf(), source })?;
        for (part, (name, text)) in documents.into_iter().enumerate() {
            let name = format!("{name}_{:05}.vtp", self.count);
            let f = dir.join(&name);
            std::fs::write(&f, text).map_err(|source| Error::Io { file: f, source })?;
            self.entries.push((time, name, part as u8));
        }
        self.count += 1;
        let f = dir.join(COLLECTION);
        std::fs::write(&f, self.collection()).map_err(|source| Error::Io { file: f, source })
    }

    /// The `.pvd` text of the snapshots written so far.
    pub fn collection(&self) -> String {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<Collection>\n",
        );
        for (t, file, part) in &self.entries {
            // {:e} prints the shortest text that reads back as the same f64
            let _ = writeln!(s, "<DataSet timestep=\"{t:e}\" group=\"\" part=\"{part}\" file=\"{file}\"/>");
        }
        s.push_str("</Collection>\n</VTKFile>\n");
        s
    }
}

/// The snapshot folder of the output folder `out`.
pub fn folder(out: &Path) -> PathBuf {
    out.join(FOLDER)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snapshots_are_due_a_period_apart_and_never_in_bursts_to_catch_up() {
        let dir = std::env::temp_dir().join(format!("saltus_paraview_{}", std::process::id()));
        let mut s = Series::default();
        let doc = || Ok(vec![("particles", "<x/>".to_string())]);
        s.write(&dir, 0.0, 0.5, doc()).unwrap();
        assert_eq!(s.next, 0.5);
        // far behind the clock: one snapshot, the next at the boundary after now
        s.write(&dir, 2.2, 0.5, doc()).unwrap();
        assert_eq!((s.len(), s.next), (2, 2.5));
        let e = s.write(&dir, 2.5, 0.5, Err("array `u_f` holds a non-finite value".into())).unwrap_err();
        assert!(e.to_string().contains("u_f"), "{e}");
        assert_eq!(s.len(), 2, "a refused snapshot is not counted");
        let pvd = std::fs::read_to_string(dir.join(COLLECTION)).unwrap();
        assert!(pvd.contains("timestep=\"2.2e0\"") && pvd.contains("particles_00001.vtp"), "{pvd}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
