//! A closures file (`saltus run SCENE --closures FILE`): `[closures.*]` tables that replace
//! the scene's, family by family, and an optional `[fit]` table of metadata (the window,
//! residuals and errors of `saltus diagnose --fit`), which is read as a record and ignored.
//! Anything else is refused naming the file and the key.

use std::path::{Path, PathBuf};

use super::overrides::parse_table;
use crate::closure::Family;
use crate::error::{Error, Result};

/// Top-level keys a closures file may hold.
pub const CLOSURES_FILE_KEYS: [&str; 2] = ["closures", "fit"];

/// The `[closures]` table of closures file `path`, checked: only [`CLOSURES_FILE_KEYS`]
/// at the top, only known families under `[closures]`, each a table with a `type`. The
/// keys inside each table are checked when the scene loads it (errors then name this
/// file, see [`Scene::from_file_with_closures`](super::Scene::from_file_with_closures)).
pub fn closures_file_tables(path: &Path) -> Result<toml::Table> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io { file: path.into(), source })?;
    let mut table = parse_table(&text, path)?;
    let key_err = |key: String, message: String| Error::Key { file: path.into(), key, message };
    if let Some(k) = table.keys().find(|k| !CLOSURES_FILE_KEYS.contains(&k.as_str())) {
        return Err(key_err(
            k.clone(),
            "unknown key of a closures file; allowed: [closures.<family>] tables and a [fit] table of metadata".into(),
        ));
    }
    if let Some(fit) = table.get("fit").filter(|v| !v.is_table()) {
        return Err(key_err("fit".into(), format!("expected a table of metadata, found {}", fit.type_str())));
    }
    let closures = match table.remove("closures") {
        Some(toml::Value::Table(t)) => t,
        Some(other) => return Err(key_err("closures".into(), format!("expected a table, found {}", other.type_str()))),
        None => {
            return Err(key_err("closures".into(), "missing; a closures file holds [closures.<family>] tables".into()))
        }
    };
    if closures.is_empty() {
        return Err(key_err("closures".into(), "empty; give at least one [closures.<family>] table".into()));
    }
    let known: Vec<_> = Family::ALL.iter().map(|f| f.key()).collect();
    for (k, v) in &closures {
        if Family::from_key(k).is_none() {
            return Err(key_err(
                format!("closures.{k}"),
                format!("unknown closure family; known: {}", known.join(", ")),
            ));
        }
        if !v.is_table() {
            return Err(key_err(format!("closures.{k}"), format!("expected a closure table, found {}", v.type_str())));
        }
    }
    Ok(closures)
}

/// Replace the `[closures.<family>]` tables of raw scene `table` by those of closures
/// file `path` (and remove those families from the solvers' `[solver.<face>.closures]`)
/// and record the file in `meta.closures_file`; returns the families
/// replaced (their keys).
pub fn apply_closures_file(table: &mut toml::Table, path: &Path) -> Result<Vec<String>> {
    let given = closures_file_tables(path)?;
    let families: Vec<String> = given.keys().cloned().collect();
    let closures = table.entry("closures").or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let Some(closures) = closures.as_table_mut() else {
        return Err(Error::Invalid(format!(
            "{}: the scene's `closures` is not a table, so the tables of the closures file cannot replace it",
            path.display()
        )));
    };
    for (k, v) in given {
        closures.insert(k, v);
    }
    // the file's closures are those that run, whichever solver: they replace the
    // solvers' own tables of their families too
    for face in super::overrides::FACES {
        if let Some(tables) = super::overrides::face_tables_mut(table, face) {
            tables.retain(|k, _| !families.iter().any(|f| f == k));
        }
    }
    let meta = table.entry("meta").or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let Some(meta) = meta.as_table_mut() {
        meta.insert("closures_file".into(), toml::Value::String(absolute(path).display().to_string()));
    }
    Ok(families)
}

fn absolute(p: &Path) -> PathBuf {
    let p = if p.is_relative() {
        std::env::current_dir().map(|c| c.join(p)).unwrap_or_else(|_| p.into())
    } else {
        p.into()
    };
    p.canonicalize().unwrap_or(p)
}

/// An error of a scene whose closure tables of `families` came from closures file `path`:
/// an error under one of those tables names that file instead of the scene.
pub fn attribute(e: Error, path: &Path, families: &[String]) -> Error {
    let ours = |key: &str| {
        families.iter().any(|f| {
            let k = format!("closures.{f}");
            key == k || key.starts_with(&format!("{k}."))
        })
    };
    match e {
        Error::Key { key, message, .. } if ours(&key) => Error::Key { file: path.into(), key, message },
        Error::OutOfRange { key, value, allowed, .. } if ours(&key) => {
            Error::OutOfRange { file: path.into(), key, value, allowed }
        }
        Error::UnknownModel { key, family, name, known, .. } if ours(&key) => {
            Error::UnknownModel { file: path.into(), key, family, name, known }
        }
        other => other,
    }
}
