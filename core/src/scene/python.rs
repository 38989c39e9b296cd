//! `[python]`: the Python files or modules that register the closures a scene names
//! (`modules = ["my_laws.py"]`), imported by the Python package before the scene's
//! closures resolve (`python -m saltus run SCENE`, `saltus.run`).
//!
//! A path (an entry ending in `.py` or holding a `/`) is relative to the scene's folder
//! and written absolute in the resolved scene, so that `scene.toml` reruns from anywhere;
//! any other entry is a module name imported from Python's path. A program without a
//! Python interpreter (the `saltus` binary) refuses such a scene: its closures would not
//! be there.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// `[python]` of a scene.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Python {
    /// files (absolute once resolved) or module names, imported in order
    pub modules: Vec<String>,
}

/// Whether an entry of `modules` is a file rather than a module name.
fn is_file(entry: &str) -> bool {
    entry.ends_with(".py") || entry.contains('/') || entry.contains('\\')
}

impl Python {
    /// `[python]` from its TOML value in `file`: every file entry made absolute against
    /// the scene's folder and required to exist, every module name a dotted identifier.
    pub fn from_value(value: toml::Value, file: &Path) -> Result<Python> {
        let key = |k: String, message: String| Error::Key { file: file.into(), key: k, message };
        let mut p: Python = super::de_path(value, file, "python")?;
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        for (i, m) in p.modules.iter_mut().enumerate() {
            if is_file(m) {
                let path = super::absolute(&dir, m);
                if !Path::new(&path).is_file() {
                    return Err(key(format!("python.modules[{i}]"), format!("no Python file {path}")));
                }
                *m = path;
            } else if m.is_empty()
                || !m.split('.').all(|s| s.chars().all(|c| c.is_alphanumeric() || c == '_') && !s.is_empty())
            {
                return Err(key(
                    format!("python.modules[{i}]"),
                    format!("`{m}` is neither a Python file (`.py`, relative to the scene) nor a module name"),
                ));
            }
        }
        Ok(p)
    }

    /// The refusal of a program that cannot import the modules.
    pub fn refused(&self, file: &Path) -> Error {
        Error::Key {
            file: file.into(),
            key: "python.modules".into(),
            message: format!(
                "the scene's closures are written in Python ({}); this program has no Python interpreter: run it \
                 with `python -m saltus run {}` (the saltus Python package, pip install ./python)",
                self.modules.join(", "),
                file.display()
            ),
        }
    }
}
