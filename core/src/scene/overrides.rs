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
/// An override of a closure goes to the table of that family that runs, whichever
/// solver: `closures.<family>={...}` replaces the scene's table and those of the
/// solvers' faces (`[solver.<face>.closures.<family>]`, which it removes), and
/// `closures.<family>.<key>=v` sets the key in each of them.
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
    if let ["closures", family, rest @ ..] = parts.as_slice() {
        for face in FACES {
            let Some(tables) = face_tables_mut(table, face) else {
                continue;
            };
            if rest.is_empty() {
                tables.remove(*family);
            } else if let Some(toml::Value::Table(own)) = tables.get_mut(*family) {
                insert_at(own, rest, value.clone(), spec)?;
            }
        }
    }
    insert_at(table, &parts, value, spec)
}

/// The solvers whose `[solver.<face>.closures]` tables may replace the scene's.
pub const FACES: [&str; 2] = ["eulerian", "lagrangian"];

/// The raw `[solver.<face>.closures]` table of scene `table`, if it has one.
pub fn face_tables_mut<'a>(table: &'a mut toml::Table, face: &str) -> Option<&'a mut toml::Table> {
    table.get_mut("solver")?.get_mut(face)?.get_mut("closures")?.as_table_mut()
}

/// Put `value` at key path `parts` of `table`, making the tables on the way.
fn insert_at(table: &mut toml::Table, parts: &[&str], value: toml::Value, spec: &str) -> Result<()> {
    let Some((last, path)) = parts.split_last() else {
        return Err(Error::Invalid(format!("--set `{spec}`: empty key")));
    };
    let mut cur = table;
    for p in path {
        let entry = cur.entry(p.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(Error::Invalid(format!("--set `{spec}`: `{p}` is not a table"))),
        };
    }
    cur.insert(last.to_string(), value);
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

    #[test]
    fn a_closure_override_reaches_the_solvers_faces() {
        let text = "[closures.viscosity]\ntype = \"fry2024\"\nshields = 0.67\n\
                    [solver.lagrangian.closures.viscosity]\ntype = \"fry2024\"\nshields = 0.5\n\
                    [solver.eulerian.closures.drag]\ntype = \"stokes\"\n";
        let mut t: toml::Table = text.parse().unwrap();
        apply_override(&mut t, "closures.viscosity.shields=0.8").unwrap();
        assert_eq!(t["closures"]["viscosity"]["shields"].as_float(), Some(0.8));
        assert_eq!(t["solver"]["lagrangian"]["closures"]["viscosity"]["shields"].as_float(), Some(0.8));
        // a face without the family is not given it
        assert!(t["solver"]["eulerian"]["closures"].get("viscosity").is_none());
        apply_override(&mut t, "closures.viscosity={type=\"clear_fluid\"}").unwrap();
        assert!(t["solver"]["lagrangian"]["closures"].get("viscosity").is_none());
        apply_override(&mut t, "closures.drag={type=\"dallavalle\"}").unwrap();
        assert!(t["solver"]["eulerian"]["closures"].get("drag").is_none());
        assert_eq!(t["closures"]["drag"]["type"].as_str(), Some("dallavalle"));
    }
}
