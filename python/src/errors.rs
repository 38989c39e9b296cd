//! The exceptions of `saltus._native` and the saltus errors raised as them, with the file
//! and key path an error points at as the exception's `file` and `key` attributes.

use std::path::Path;

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use saltus_core::Error;

create_exception!(
    saltus,
    SceneError,
    PyValueError,
    "Bad input: a scene or closure table that does not load (TOML syntax, unknown key or \
     model, out-of-range value, unmet closure need, a scene its solver cannot start on). The \
     message is the command line's; `file` and `key` name the file and the key path when \
     the error has them (else None)."
);
create_exception!(
    saltus,
    RunError,
    PyRuntimeError,
    "A run that could not write its outputs (the output folder cannot be made or a file \
     cannot be written); `file` names it."
);

/// Where an error points: its file and key path, when it has them.
pub(crate) struct Place {
    pub(crate) file: Option<String>,
    pub(crate) key: Option<String>,
    /// a file that could not be read or written
    pub(crate) io: bool,
}

impl Place {
    pub(crate) fn of(e: &Error) -> Self {
        let (file, key): (Option<&Path>, Option<&str>) = match e {
            Error::Io { file, .. } | Error::Syntax { file, .. } => (Some(file), None),
            Error::Key { file, key, .. }
            | Error::UnknownModel { file, key, .. }
            | Error::OutOfRange { file, key, .. }
            | Error::UnmetNeed { file, key, .. } => (Some(file), Some(key)),
            Error::Invalid(_) => (None, None),
        };
        Place {
            file: file.map(|f| f.display().to_string()),
            key: key.map(str::to_string),
            io: matches!(e, Error::Io { .. }),
        }
    }

    /// `err` with this place as its `file` and `key` attributes.
    pub(crate) fn attach(self, py: Python<'_>, err: PyErr) -> PyErr {
        let value = err.value(py);
        // the attributes are extras: failing to set them must not hide the error itself
        let _ = value.setattr("file", self.file);
        let _ = value.setattr("key", self.key);
        err
    }
}

/// A scene that does not load (an unreadable scene file included: bad input, not a failed
/// output): [`SceneError`] with the message `saltus check` and `saltus run` print, the
/// error and its causes joined as anyhow's `{:#}` does.
pub(crate) fn load_error(py: Python<'_>, e: Error) -> PyErr {
    let place = Place::of(&e);
    let message = saltus::describe(&anyhow::Error::from(e));
    place.attach(py, SceneError::new_err(message))
}

/// A run that failed: [`RunError`] when its outputs could not be written, [`SceneError`]
/// when the solver could not be set up on the scene; the message `saltus run` prints.
pub(crate) fn run_error(py: Python<'_>, e: Error) -> PyErr {
    let place = Place::of(&e);
    let message = e.to_string();
    let err = if place.io { RunError::new_err(message) } else { SceneError::new_err(message) };
    place.attach(py, err)
}
