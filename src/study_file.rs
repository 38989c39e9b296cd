//! What the files of the studies (`compare`, `sweep`, `calibrate`) share: each is a TOML
//! file that names a base scene relative to its own folder, a `[meta]` table and closures
//! files, and every error it raises names the study file and the key at fault.

use std::path::{Path, PathBuf};

use saltus_core::scene::{de_path, parse_table, Meta};
use saltus_core::Error;
use serde::de::DeserializeOwned;

/// An error about `key` of the study file `file`.
pub fn key_error(file: &Path, key: impl Into<String>, message: impl Into<String>) -> anyhow::Error {
    Error::Key { file: file.to_path_buf(), key: key.into(), message: message.into() }.into()
}

/// A study file as read: its syntax and keys checked against `T` (unknown keys and wrong
/// types refused by name), and the folder its relative paths are resolved against.
pub fn read<T: DeserializeOwned>(path: &Path) -> anyhow::Result<(T, PathBuf)> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io { file: path.into(), source })?;
    let table = parse_table(&text, path)?;
    let raw: T = de_path(toml::Value::Table(table), path, "")?;
    Ok((raw, folder(path)))
}

/// The folder of `path`, against which the study file's relative paths are resolved.
pub fn folder(path: &Path) -> PathBuf {
    path.parent().unwrap_or(Path::new("")).to_path_buf()
}

/// The base scene `base` of the study file `path`, resolved against its folder; an error
/// on the key `base` when no such file exists.
pub fn base_scene(path: &Path, base: &str) -> anyhow::Result<PathBuf> {
    let file = folder(path).join(base);
    if !file.is_file() {
        return Err(key_error(path, "base", format!("`{base}`: no such scene file ({})", file.display())));
    }
    Ok(file)
}

/// The closures file `rel` named by `key` of the study file `path`, resolved against its
/// folder and its `[closures.<family>]` tables read, so that a broken file fails before
/// any run.
pub fn closures_file(path: &Path, key: impl Into<String>, rel: &Path) -> anyhow::Result<PathBuf> {
    let file = folder(path).join(rel);
    saltus_core::scene::closures_file_tables(&file).map_err(|e| key_error(path, key, format!("{e}")))?;
    Ok(file)
}

/// `meta` with its name, when empty, the study file's stem (or `fallback`).
pub fn named(mut meta: Meta, path: &Path, fallback: &str) -> Meta {
    if meta.name.is_empty() {
        meta.name = path.file_stem().map_or_else(|| fallback.into(), |s| s.to_string_lossy().into_owned());
    }
    meta
}
