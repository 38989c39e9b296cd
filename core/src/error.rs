//! Errors of saltus. Every user-facing error names the file, the key path and what is
//! allowed, so that a bad scene never reaches a solver.

use std::borrow::Cow;
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
    #[error("{file}:{line}:{column}: TOML syntax error: {}", clip_words(.message))]
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
    #[error("{file}: key `{}`: {}", clip_words(.key), clip_words(.message))]
    Key {
        /// offending file
        file: PathBuf,
        /// dotted key path, e.g. `closures.drag.sphericity`
        key: String,
        /// what is wrong and what is allowed
        message: String,
    },
    /// A model name that no registered closure of the family carries.
    #[error("{file}: key `{}`: unknown {family} model `{}`; known: {known}", clip_words(.key), clip_words(.name))]
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
    #[error("{file}: key `{}` = {}: out of range, allowed {allowed}", clip_words(.key), clip_words(.value))]
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
    #[error("{}", clip_words(.0))]
    Invalid(String),
}

impl Error {
    /// Attach a file to a [`crate::ParamError`] raised under table `prefix`.
    pub fn from_param(file: impl Into<PathBuf>, prefix: &str, e: crate::ParamError) -> Self {
        let key = if prefix.is_empty() { e.key } else { format!("{prefix}.{}", e.key) };
        Error::OutOfRange { file: file.into(), key, value: e.value, allowed: e.allowed }
    }
}

/// Longest word an error repeats in full: far above any key path, model name or file
/// path of a scene.
pub const LONGEST_WORD: usize = 240;

/// What ends a word of [`clip_words`]: blanks and the punctuation that quotes or follows
/// a key, a name or a value in a message.
fn ends_word(c: char) -> bool {
    c.is_whitespace() || "`'\",;:()[]{}=<>".contains(c)
}

/// `text` with every word (a run of characters between blanks and quoting punctuation)
/// longer than [`LONGEST_WORD`] cut to its first 60 characters and its length, so that
/// a key, a name or a value pasted by mistake (a megabyte of it) is named, not echoed in
/// full.
pub fn clip_words(text: &str) -> Cow<'_, str> {
    if !text.split(ends_word).any(|w| w.len() > LONGEST_WORD) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len().min(4096));
    let mut rest = text;
    loop {
        let start = rest.find(|c: char| !ends_word(c)).unwrap_or(rest.len());
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        if rest.is_empty() {
            break;
        }
        let end = rest.find(ends_word).unwrap_or(rest.len());
        let word = &rest[..end];
        let chars = word.chars().count();
        if chars > LONGEST_WORD {
            let head: String = word.chars().take(60).collect();
            out.push_str(&format!("{head}... ({chars} characters)"));
        } else {
            out.push_str(word);
        }
        rest = &rest[end..];
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_megabyte_key_is_named_by_its_start_and_length() {
        let key = format!("domain.{}", "k".repeat(1_000_000));
        let e = Error::Key { file: "s.toml".into(), key: key.clone(), message: format!("unknown field `{key}`") };
        let text = e.to_string();
        assert!(text.len() < 400, "{} characters", text.len());
        assert!(text.contains("key `domain.kkkk") && text.ends_with("(1000007 characters)`"), "{text}");
        // words of ordinary length, blanks included, are kept as they are
        let e = Error::Key { file: "s.toml".into(), key: "a.b".into(), message: "two  words\tand é".into() };
        assert_eq!(e.to_string(), "s.toml: key `a.b`: two  words\tand é");
    }
}
