//! Errors of saltus. Every user-facing error names the file, the key path and what is
//! allowed, so that a bad scene never reaches a solver.

use std::path::PathBuf;

/// Result alias of saltus-core.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong before or during a run, with enough context to fix it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file or folder could not be read or written.
    #[error("{file}: {source}")]
    Io {
        /// offending file
        file: PathBuf,
        /// underlying error
        #[source]
        source: std::io::Error,
    },
    /// TOML syntax error, with line and column (1-based).
    #[error("{file}:{line}:{column}: TOML syntax error: {message}")]
    Syntax {
        /// offending file
        file: PathBuf,
        /// line, 1-based
        line: usize,
        /// column, 1-based
        column: usize,
        /// parser message
        message: String,
    },
    /// A key is missing, unknown or of the wrong type.
    #[error("{file}: key `{key}`: {message}")]
    Key {
        /// offending file
        file: PathBuf,
        /// dotted key path, e.g. `closures.drag.sphericity`
        key: String,
        /// what is wrong and what is allowed
        message: String,
    },
    /// A model name that no registered closure of the family carries.
    #[error("{file}: key `{key}`: unknown {family} model `{name}`; known: {known}")]
    UnknownModel {
        /// offending file
        file: PathBuf,
        /// dotted key path of the `type` key
        key: String,
        /// closure family
        family: String,
        /// name given
        name: String,
        /// comma-separated registered names
        known: String,
    },
    /// A parameter outside its valid range.
    #[error("{file}: key `{key}` = {value}: out of range, allowed {allowed}")]
    OutOfRange {
        /// offending file
        file: PathBuf,
        /// dotted key path
        key: String,
        /// value given
        value: String,
        /// allowed range, e.g. `(0, 1]`
        allowed: String,
    },
    /// A closure needs a field that no other closure of the scene provides.
    #[error("{file}: closure `{model}` ({key}) needs {field}, which {provider}")]
    UnmetNeed {
        /// offending file
        file: PathBuf,
        /// dotted key of the needing closure
        key: String,
        /// model name of the needing closure
        model: String,
        /// missing field
        field: String,
        /// sentence naming who should provide it
        provider: String,
    },
    /// Any other invalid input (CSV columns, command-line values ...).
    #[error("{0}")]
    Invalid(String),
}

impl Error {
    /// Attach a file to a [`crate::ParamError`] raised under table `prefix`.
    pub fn from_param(file: impl Into<PathBuf>, prefix: &str, e: crate::ParamError) -> Self {
        let key = if prefix.is_empty() { e.key } else { format!("{prefix}.{}", e.key) };
        Error::OutOfRange { file: file.into(), key, value: e.value, allowed: e.allowed }
    }
}
