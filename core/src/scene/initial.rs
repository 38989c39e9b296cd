//! `domain.initial_profiles`: a profiles CSV the Eulerian column starts from instead of
//! rest (an exact solution at the start time, a developed state of another run).

use std::path::Path;

use crate::error::{Error, Result};

/// The key, for messages.
pub const KEY: &str = "domain.initial_profiles";

/// Columns the column takes; `z` and `u_f` are required, the others default to clear fluid
/// (phi 0), grains moving with the fluid (u_p = u_f) and the scene's own temperature.
pub const COLUMNS: [&str; 5] = ["z", "phi", "u_f", "u_p", "theta_g"];

/// Most rows of a profiles file.
const MAX_ROWS: usize = 1_000_000;

/// Read the profiles file `csv` of scene `scene`: a header of names, then rows of numbers
/// separated by commas, `#` lines ignored; the columns of [`COLUMNS`] it has, in that
/// order, `z` increasing strictly and every value finite (other columns, as a run's
/// `profiles.csv` has them, are ignored). phi must lie in [0, 1).
pub fn read(csv: &Path, scene: &Path) -> Result<Vec<(String, Vec<f64>)>> {
    let err = |message: String| Error::Key { file: scene.into(), key: KEY.into(), message };
    let text = std::fs::read_to_string(csv).map_err(|e| err(format!("{}: {e}", csv.display())))?;
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(err(format!("{}: empty; a header of names (z, u_f, ...) and rows of numbers", csv.display())));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let index = |name: &str| names.iter().position(|n| *n == name);
    let wanted: Vec<(&str, usize)> = COLUMNS.iter().filter_map(|c| Some((*c, index(c)?))).collect();
    for required in ["z", "u_f"] {
        if index(required).is_none() {
            return Err(err(format!(
                "{}: no `{required}` column (header {names:?}); the columns taken are {COLUMNS:?}, z and u_f required",
                csv.display()
            )));
        }
    }
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); wanted.len()];
    for (n, line) in lines {
        let at = format!("{} line {}", csv.display(), n + 1);
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(err(format!("{at}: {} fields, the header has {}", fields.len(), names.len())));
        }
        for ((name, i), col) in wanted.iter().zip(columns.iter_mut()) {
            let v: f64 =
                fields[*i].parse().map_err(|_| err(format!("{at}: `{name}` = `{}` is not a number", fields[*i])))?;
            if !v.is_finite() || (*name == "phi" && !(0.0..1.0).contains(&v)) {
                let allowed = if *name == "phi" { "a volume fraction in [0, 1)" } else { "a finite number" };
                return Err(err(format!("{at}: `{name}` = {v}; {allowed} is needed")));
            }
            col.push(v);
        }
        if columns[0].len() > MAX_ROWS {
            return Err(err(format!("{}: more than {MAX_ROWS} rows", csv.display())));
        }
    }
    let z = &columns[0];
    if z.len() < 2 {
        return Err(err(format!("{}: {} rows; at least two are needed", csv.display(), z.len())));
    }
    if let Some(w) = z.windows(2).find(|w| w[1] <= w[0]) {
        return Err(err(format!("{}: z = {} after {}; z must increase strictly", csv.display(), w[1], w[0])));
    }
    Ok(wanted.into_iter().map(|(n, _)| n.to_string()).zip(columns).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, text: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("saltus-initial-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("p.csv");
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn a_profiles_file_gives_its_known_columns_in_order() {
        let p = file("ok", "# exact solution\nu_f,z,other\n0.1,0.0,7\n0.2,1e-3,8\n");
        let c = read(&p, Path::new("scene.toml")).unwrap();
        assert_eq!(c, vec![("z".to_string(), vec![0.0, 1e-3]), ("u_f".to_string(), vec![0.1, 0.2])]);
    }

    #[test]
    fn bad_files_are_refused_by_key_and_line() {
        for (name, text, needle) in [
            ("noz", "u_f\n0.1\n0.2\n", "no `z`"),
            ("nan", "z,u_f\n0,0.1\n1,nan\n", "line 3"),
            ("empty_cell", "z,u_f\n0,0.1\n1,\n", "not a number"),
            ("order", "z,u_f\n1,0.1\n0,0.2\n", "increase"),
            ("phi", "z,u_f,phi\n0,0.1,1.2\n1,0.2,0\n", "[0, 1)"),
            ("one_row", "z,u_f\n0,0.1\n", "two"),
            ("fields", "z,u_f\n0,0.1,3\n1,0.2\n", "fields"),
            ("blank", "", "empty"),
        ] {
            let e = read(&file(name, text), Path::new("scene.toml")).unwrap_err().to_string();
            assert!(e.contains(KEY) && e.contains(needle), "{name}: {e}");
        }
        let e = read(Path::new("/nonexistent/p.csv"), Path::new("scene.toml")).unwrap_err().to_string();
        assert!(e.contains(KEY) && e.contains("/nonexistent/p.csv"), "{e}");
    }
}
