//! Checkpoints: the state a run continues from, bit for bit (`saltus run SCENE --restart
//! DIR`).
//!
//! `DIR/checkpoint.bin` is
//!
//! ```text
//! "SALTUSCP" (8 bytes) | format version (u32 LE) | body length (u64 LE) | body | FNV-1a 64 of the body (u64 LE)
//! ```
//!
//! with the body in bincode: the program that wrote it, the solver, the resolved
//! scene (TOML text), the driver's cadences ([`Cadence`]) and the solver's own state
//! ([`super::Stepper::save`]; bincode too, every f64 as its 8 bytes, so the state reads
//! back exactly). A new file is written beside the old one and renamed over it, so that a
//! run killed while writing keeps its previous checkpoint. The format version changes
//! whenever the layout of a saved state does; a file of another version is refused.
//!
//! A restart is refused when the scene differs from the checkpoint's in anything but the
//! keys that do not change the state so far ([`may_differ`]: output settings, the name and
//! description, the reference data, the end time, the step cap, the thread count, the VTK
//! period, whether a steady state ends the run, and the numerics of the solver that is not
//! running); the error names every key that differs.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use bincode::Options as _;
use saltus_core::Error;
use serde::{Deserialize, Serialize};

use super::paraview::Series;
use super::{Clock, Phase};

/// File name of the checkpoint in its folder.
pub use crate::output::CHECKPOINT_FILE as FILE;
/// First bytes of a checkpoint.
const MAGIC: &[u8; 8] = b"SALTUSCP";
/// Layout version of the file and of every saved state (2: the DEM's statistics carry
/// the blocking of qs and the temperature history; 3: the DEM carries the half-cylinder
/// bottom, its histories and the walls' own law, and the contact law its normal force;
/// 4: the DEM state is the solver's `State` as one struct, the ParaView series and the
/// driver's clock travel with the cadences; 5: the DEM carries the time average of the
/// phases' relative velocity of Cheng's eq 24; 6: the DEM engine keeps no clock of its
/// own, the solver's state is the one clock).
pub const VERSION: u32 = 6;

/// Where the cadences are: part of a checkpoint, so that a restarted run writes the rows
/// and snapshots the uninterrupted run would have.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Cadence {
    /// phase of the last unit of work seen, `None` before the first
    pub phase: Option<Phase>,
    /// flow time of the next row (s)
    pub next_sample: f64,
    /// rows written on the cadence (the row of an ending is not counted: a restart
    /// drops it)
    pub rows: u64,
    /// steps of the last row written, so that the ending does not repeat it
    pub last_steps: Option<u64>,
    /// snapshots written
    pub snapshots: u64,
    /// flow time of the next snapshot (s)
    pub next_snapshot: f64,
    /// time of the current phase at which the next checkpoint is due (s)
    pub next_checkpoint: f64,
    /// the ParaView snapshots written and the time of the next
    pub paraview: Series,
    /// the driver's clock at the checkpoint (its flow time carries over a restart)
    pub clock: Clock,
}

/// What a checkpoint holds besides its framing.
#[derive(Serialize, Deserialize)]
struct Body {
    /// program version and git revision that wrote it
    program: String,
    /// solver name
    solver: String,
    /// the resolved scene, as TOML text
    scene: String,
    /// the driver's cadences
    cadence: Cadence,
    /// the solver's state
    state: Vec<u8>,
}

/// A checkpoint read back, ready for a restart.
#[derive(Clone, Debug)]
pub struct Restart {
    /// the folder it was read from (the old run's outputs)
    pub dir: PathBuf,
    /// the checkpoint file
    pub file: PathBuf,
    /// solver that wrote it
    pub solver: String,
    /// resolved scene of the run that wrote it (TOML)
    pub scene: String,
    /// the driver's cadences at the checkpoint
    pub cadence: Cadence,
    /// the solver's state
    pub state: Vec<u8>,
}

impl Restart {
    /// The checkpoint's scene resolved again by this program (relative paths against
    /// `path`), so that a key added since it was written (absent there) takes its
    /// default, which is the behaviour the checkpoint ran with; a scene this version
    /// cannot read is given as written.
    pub fn resolved_scene(&self, path: &Path) -> String {
        self.scene
            .parse::<toml::Table>()
            .ok()
            .and_then(|t| saltus_core::scene::Scene::from_table(t, path).ok())
            .and_then(|s| s.to_toml().ok())
            .unwrap_or_else(|| self.scene.clone())
    }
}

fn program() -> String {
    format!("saltus {} ({})", env!("CARGO_PKG_VERSION"), crate::output::GIT_REVISION)
}

fn options() -> impl bincode::Options {
    bincode::DefaultOptions::new()
}

/// FNV-1a, 64 bits: catches a truncated or damaged file before anything is decoded.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// Write `dir/checkpoint.bin` for `solver` run from the resolved `scene` text.
pub fn write(dir: &Path, solver: &str, scene: &str, cadence: &Cadence, state: &[u8]) -> Result<(), Error> {
    let file = dir.join(FILE);
    let body = Body {
        program: program(),
        solver: solver.to_string(),
        scene: scene.to_string(),
        cadence: cadence.clone(),
        state: state.to_vec(),
    };
    let body = options()
        .serialize(&body)
        .map_err(|e| Error::Invalid(format!("{}: cannot encode the checkpoint: {e}", file.display())))?;
    let tmp = dir.join(format!("{FILE}.partial"));
    let io = |f: &Path| {
        let f = f.to_path_buf();
        move |source| Error::Io { file: f, source }
    };
    let mut w = std::io::BufWriter::new(std::fs::File::create(&tmp).map_err(io(&tmp))?);
    w.write_all(MAGIC).map_err(io(&tmp))?;
    w.write_all(&VERSION.to_le_bytes()).map_err(io(&tmp))?;
    w.write_all(&(body.len() as u64).to_le_bytes()).map_err(io(&tmp))?;
    w.write_all(&body).map_err(io(&tmp))?;
    w.write_all(&fnv1a(&body).to_le_bytes()).map_err(io(&tmp))?;
    let f = w.into_inner().map_err(|e| Error::Io { file: tmp.clone(), source: e.into_error() })?;
    // on disk before it replaces the previous checkpoint
    f.sync_all().map_err(io(&tmp))?;
    std::fs::rename(&tmp, &file).map_err(io(&file))
}

/// The run folder of a checkpoint given as `--restart` gives it: the folder itself, or
/// the folder of the checkpoint file (`.` for a file in the current folder).
pub fn folder(path: &Path) -> PathBuf {
    if path.is_file() {
        match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    } else {
        path.to_path_buf()
    }
}

/// Read the checkpoint of `path`: a folder holding `checkpoint.bin` (the output folder of
/// the run), or the file itself. Errors name the file and what is wrong with it.
pub fn read(path: &Path) -> Result<Restart, Error> {
    let (dir, file) = if path.is_dir() {
        (path.to_path_buf(), path.join(FILE))
    } else if path.is_file() {
        (folder(path), path.to_path_buf())
    } else {
        return Err(Error::Invalid(format!(
            "--restart {}: no such folder or file (give the output folder of the run to continue, which holds {FILE})",
            path.display()
        )));
    };
    let bytes = std::fs::read(&file).map_err(|source| Error::Io { file: file.clone(), source })?;
    let bad = |what: String| Error::Invalid(format!("{}: not a usable checkpoint: {what}", file.display()));
    if bytes.len() < 28 || &bytes[..8] != MAGIC {
        return Err(bad(format!("it does not start with the checkpoint header ({} bytes)", bytes.len())));
    }
    let word = |at: usize, n: usize| {
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&bytes[at..at + n]);
        u64::from_le_bytes(b)
    };
    let version = word(8, 4);
    if version != u64::from(VERSION) {
        return Err(bad(format!(
            "format version {version}, this program reads version {VERSION} (restart with the program that wrote it)"
        )));
    }
    let len = word(12, 8);
    let end = 20u64.checked_add(len).filter(|&e| e.checked_add(8) == Some(bytes.len() as u64));
    let Some(end) = end.map(|e| e as usize) else {
        return Err(bad(format!("truncated or extended: {} bytes for a body of {len}", bytes.len())));
    };
    let body = &bytes[20..end];
    if fnv1a(body) != word(end, 8) {
        return Err(bad("damaged: the checksum does not match".into()));
    }
    let body: Body =
        options().with_limit(body.len() as u64).deserialize(body).map_err(|e| bad(format!("cannot decode: {e}")))?;
    Ok(Restart { dir, file, solver: body.solver, scene: body.scene, cadence: body.cadence, state: body.state })
}

/// Keys of a resolved scene that may differ between a checkpoint and its restart: they
/// change neither the state so far nor the steps to come.
pub fn may_differ(key: &str, solver: &str) -> bool {
    const ALWAYS: [&str; 3] = ["output", "meta", "reference"];
    const LAGRANGIAN: [&str; 6] = [
        "solver.eulerian",
        "solver.lagrangian.end_time",
        "solver.lagrangian.max_steps",
        "solver.lagrangian.threads",
        "solver.lagrangian.vtk_period",
        "solver.lagrangian.stop_when_steady",
    ];
    const EULERIAN: [&str; 4] =
        ["solver.lagrangian", "solver.eulerian.end_time", "solver.eulerian.max_steps", "particles.contact"];
    let listed = |k: &&str| key == *k || key.strip_prefix(*k).is_some_and(|rest| rest.starts_with('.'));
    ALWAYS.iter().any(listed)
        || match solver {
            "lagrangian" => LAGRANGIAN.iter().any(listed),
            "eulerian" => EULERIAN.iter().any(listed),
            _ => false,
        }
}

/// Keys in which the resolved scenes `saved` (the checkpoint's) and `now` differ, other
/// than those that [`may_differ`], with both values (`-` where absent).
pub fn scene_differences(saved: &str, now: &str, solver: &str) -> Result<Vec<String>, String> {
    let parse = |t: &str, what: &str| t.parse::<toml::Table>().map_err(|e| format!("{what} scene: {e}"));
    let (a, b) = (parse(saved, "the checkpoint's")?, parse(now, "this")?);
    let mut out = Vec::new();
    diff("", &toml::Value::Table(a), &toml::Value::Table(b), &|k| may_differ(k, solver), &mut out);
    Ok(out)
}

/// Keys in which the resolved scenes `saved` (the checkpoint's) and `now` differ among
/// `keys` and the keys under them, with both values (`-` where absent).
pub fn scene_differences_in(saved: &str, now: &str, keys: &[&str]) -> Result<Vec<String>, String> {
    let parse = |t: &str, what: &str| t.parse::<toml::Table>().map_err(|e| format!("{what} scene: {e}"));
    let (a, b) = (parse(saved, "the checkpoint's")?, parse(now, "this")?);
    let under = |key: &str, k: &str| key == k || key.strip_prefix(k).is_some_and(|rest| rest.starts_with('.'));
    // a table above a listed key is entered, everything beside the listed keys skipped
    let skip = |key: &str| !keys.iter().any(|k| under(key, k) || under(k, key));
    let mut out = Vec::new();
    diff("", &toml::Value::Table(a), &toml::Value::Table(b), &skip, &mut out);
    Ok(out)
}

fn diff(key: &str, a: &toml::Value, b: &toml::Value, skip: &dyn Fn(&str) -> bool, out: &mut Vec<String>) {
    if !key.is_empty() && skip(key) {
        return;
    }
    if let (toml::Value::Table(x), toml::Value::Table(y)) = (a, b) {
        let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
        keys.sort();
        keys.dedup();
        for k in keys {
            let sub = if key.is_empty() { k.clone() } else { format!("{key}.{k}") };
            match (x.get(k), y.get(k)) {
                (Some(u), Some(v)) => diff(&sub, u, v, skip, out),
                (u, v) if !skip(&sub) => out.push(format!("{sub} ({} in the checkpoint, {} now)", show(u), show(v))),
                _ => {}
            }
        }
    } else if a != b {
        out.push(format!("{key} ({} in the checkpoint, {} now)", show(Some(a)), show(Some(b))));
    }
}

fn show(v: Option<&toml::Value>) -> String {
    match v {
        None => "-".into(),
        Some(toml::Value::String(s)) => format!("\"{s}\""),
        Some(v) => {
            let t = v.to_string();
            if t.len() > 60 {
                format!("{}...", &t[..t.char_indices().nth(57).map_or(t.len(), |(i, _)| i)])
            } else {
                t
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_checkpoint_reads_back_and_damage_is_named() {
        let dir = std::env::temp_dir().join(format!("saltus_checkpoint_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let cadence = Cadence { rows: 7, next_sample: 0.5, ..Cadence::default() };
        let state = vec![1u8, 2, 3, 255];
        write(&dir, "lagrangian", "seed = 3\n", &cadence, &state).unwrap();
        let r = read(&dir).unwrap();
        assert_eq!(
            (r.solver.as_str(), r.scene.as_str(), r.cadence.clone(), r.state),
            ("lagrangian", "seed = 3\n", cadence, state)
        );
        let file = dir.join(FILE);
        let mut bytes = std::fs::read(&file).unwrap();
        let n = bytes.len();
        // a checkpoint of the previous layout, intact otherwise, is refused by its version
        let mut older = bytes.clone();
        older[8..12].copy_from_slice(&(VERSION - 1).to_le_bytes());
        std::fs::write(&file, &older).unwrap();
        let e = read(&dir).unwrap_err().to_string();
        assert!(e.contains(&format!("format version {}, this program reads version {VERSION}", VERSION - 1)), "{e}");
        bytes[n - 12] ^= 1;
        std::fs::write(&file, &bytes).unwrap();
        let e = read(&dir).unwrap_err().to_string();
        assert!(e.contains("checkpoint.bin") && e.contains("checksum"), "{e}");
        std::fs::write(&file, &bytes[..n / 2]).unwrap();
        let e = read(&dir).unwrap_err().to_string();
        assert!(e.contains("checkpoint.bin") && e.contains("truncated"), "{e}");
        std::fs::write(&file, b"hello").unwrap();
        assert!(read(&dir).unwrap_err().to_string().contains("header"));
        let e = read(&dir.join("nope")).unwrap_err().to_string();
        assert!(e.contains("--restart") && e.contains("nope"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn scene_differences_name_the_keys_and_skip_the_free_ones() {
        let a = "seed = 1\n[solver.lagrangian]\nend_time = 1.0\nsettle_time = 0.1\n[output]\ndir = \"a\"\n";
        let b = "seed = 2\n[solver.lagrangian]\nend_time = 5.0\nsettle_time = 0.2\n[output]\ndir = \"b\"\n";
        let d = scene_differences(a, b, "lagrangian").unwrap();
        assert_eq!(
            d,
            ["seed (1 in the checkpoint, 2 now)", "solver.lagrangian.settle_time (0.1 in the checkpoint, 0.2 now)"]
        );
        assert!(scene_differences(a, a, "lagrangian").unwrap().is_empty());
    }

    #[test]
    fn differences_in_listed_keys_skip_every_other_key() {
        let a = "seed = 1\n[solver.lagrangian]\nlength = 0.03\nend_time = 1.0\n[particles]\nfriction = 0.4\n";
        let b = "seed = 2\n[solver.lagrangian]\nlength = 0.04\nend_time = 5.0\n[particles]\nfriction = 0.5\n";
        let d = scene_differences_in(a, b, &["particles", "solver.lagrangian.length"]).unwrap();
        assert_eq!(
            d,
            [
                "particles.friction (0.4 in the checkpoint, 0.5 now)",
                "solver.lagrangian.length (0.03 in the checkpoint, 0.04 now)"
            ]
        );
        let c = "seed = 2\n[solver.lagrangian]\nlength = 0.03\n[particles]\nfriction = 0.4\n";
        assert!(scene_differences_in(a, c, &["particles", "solver.lagrangian.length"]).unwrap().is_empty());
    }
}
