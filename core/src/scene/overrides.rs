//! Raw scene text: TOML parsing with line and column, and `--set KEY=VALUE` overrides.

use std::path::Path;

use crate::error::{Error, Result};

/// Parse TOML text into a table; syntax errors carry line and column.
pub fn parse_table(text: &str, file: &Path) -> Result<toml::Table> {
    text.parse::<toml::Table>().map_err(|e| {
        let (line, column) = e.span().map(|s| line_col(text, s.start)).unwrap_or((0, 0));
        Error::Syntax { file: file.to_path_buf(), line, column, message: e.message().to_string() }
    })
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    // spans are byte offsets; fall back to the whole text rather than slice mid-character
    let before = text.get(..offset.min(text.len())).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Apply one `KEY=VALUE` override to a raw scene table. VALUE is parsed as a TOML value
/// (so `0.3`, `"text"`, `{type = "stokes"}` work); a bare word is taken as a string.
pub fn apply_override(table: &mut toml::Table, spec: &str) -> Result<()> {
    let (key, raw) =
        spec.split_once('=').ok_or_else(|| Error::Invalid(format!("--set `{spec}`: expected KEY=VALUE")))?;
    let key = key.trim();
    let raw = raw.trim();
    let value = format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()));
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(Error::Invalid(format!("--set `{spec}`: empty key segment")));
    }
    let mut cur = table;
    for p in &parts[..parts.len() - 1] {
        let entry = cur.entry(p.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(Error::Invalid(format!("--set `{spec}`: `{p}` is not a table"))),
        };
    }
    cur.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syntax_error_has_line_and_column() {
        let e = parse_table("a = 1\nb = = 2\n", Path::new("x.toml")).unwrap_err();
        match e {
            Error::Syntax { line, column, .. } => {
                assert_eq!(line, 2);
                assert!(column >= 3);
            }
            other => panic!("unexpected {other}"),
        }
    }

    #[test]
    fn override_sets_nested_keys_and_tables() {
        let mut t: toml::Table = "[closures.drag]\ntype = \"dallavalle\"\n".parse().unwrap();
        apply_override(&mut t, "closures.drag={type=\"stokes\"}").unwrap();
        apply_override(&mut t, "physics.slope=0.05").unwrap();
        assert_eq!(t["closures"]["drag"]["type"].as_str(), Some("stokes"));
        assert_eq!(t["physics"]["slope"].as_float(), Some(0.05));
        assert!(apply_override(&mut t, "noequals").is_err());
    }
}
