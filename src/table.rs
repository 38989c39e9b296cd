//! Column tables read from and written to CSV.

use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context};

/// Named columns of equal length.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// column names, in order
    pub names: Vec<String>,
    /// column values, same order as `names`
    pub columns: Vec<Vec<f64>>,
}

impl Table {
    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, Vec::len)
    }

    /// Column by name.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.names.iter().position(|n| n == name).map(|i| self.columns[i].as_slice())
    }

    /// Column by name, mutable.
    pub fn column_mut(&mut self, name: &str) -> Option<&mut Vec<f64>> {
        self.names.iter().position(|n| n == name).map(|i| &mut self.columns[i])
    }

    /// Append a column (must have `rows()` entries unless the table is empty).
    pub fn push(&mut self, name: impl Into<String>, values: Vec<f64>) {
        self.names.push(name.into());
        self.columns.push(values);
    }

    /// Read a CSV whose first line names the columns; every cell must be a number.
    pub fn read_csv(reader: impl std::io::Read, origin: &str) -> anyhow::Result<Table> {
        Self::read_csv_cells(reader, origin, false)
    }

    /// Read a run's `profiles.csv`: as [`Table::read_csv`], but an empty cell (a value
    /// undefined there, see [`saltus_solvers::Profiles::to_csv`]) is read as NaN.
    pub fn read_profiles_file(path: &Path) -> anyhow::Result<Table> {
        let f = std::fs::File::open(path).with_context(|| format!("{}: cannot open", path.display()))?;
        Self::read_csv_cells(f, &path.display().to_string(), true)
    }

    fn read_csv_cells(reader: impl std::io::Read, origin: &str, empty_is_undefined: bool) -> anyhow::Result<Table> {
        let mut rdr = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(reader);
        let names: Vec<String> = rdr
            .headers()
            .with_context(|| format!("{origin}: cannot read the header line"))?
            .iter()
            .map(str::to_string)
            .collect();
        if names.is_empty() || names.iter().any(String::is_empty) {
            bail!("{origin}: the header line must name every column");
        }
        let mut columns = vec![Vec::new(); names.len()];
        for (i, rec) in rdr.records().enumerate() {
            let rec = rec.with_context(|| format!("{origin}: row {}", i + 2))?;
            if rec.len() != names.len() {
                bail!("{origin}: row {} has {} cells, the header has {}", i + 2, rec.len(), names.len());
            }
            for (j, cell) in rec.iter().enumerate() {
                if empty_is_undefined && cell.is_empty() {
                    columns[j].push(f64::NAN);
                    continue;
                }
                let v: f64 = cell.parse().with_context(|| {
                    format!("{origin}: row {}, column `{}`: `{cell}` is not a number", i + 2, names[j])
                })?;
                if !v.is_finite() {
                    bail!("{origin}: row {}, column `{}`: `{cell}` is not a finite number", i + 2, names[j]);
                }
                columns[j].push(v);
            }
        }
        Ok(Table { names, columns })
    }

    /// Read a CSV file.
    pub fn read_csv_file(path: &Path) -> anyhow::Result<Table> {
        let f = std::fs::File::open(path).with_context(|| format!("{}: cannot open", path.display()))?;
        Self::read_csv(f, &path.display().to_string())
    }

    /// Write as CSV (full precision, round-trippable); a value that is not finite (C_D at
    /// Re_p = 0, f of a laminar wall law at rest) is undefined there and written as an
    /// empty cell, as in a run's `profiles.csv`.
    pub fn write_csv(&self, writer: impl Write) -> anyhow::Result<()> {
        let mut w = csv::Writer::from_writer(writer);
        w.write_record(&self.names)?;
        for r in 0..self.rows() {
            w.write_record(self.columns.iter().map(|c| {
                if c[r].is_finite() {
                    format!("{}", c[r])
                } else {
                    String::new()
                }
            }))?;
        }
        w.flush()?;
        Ok(())
    }

    /// Write a CSV file, creating parent folders.
    pub fn write_csv_file(&self, path: &Path) -> anyhow::Result<()> {
        if let Some(dir) = path.parent() {
            if !dir.as_os_str().is_empty() {
                std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
            }
        }
        let f = std::fs::File::create(path).with_context(|| format!("{}: cannot create", path.display()))?;
        self.write_csv(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_values_are_written_as_empty_cells() {
        let mut t = Table::default();
        t.push("re_p", vec![0.0, 1.0, 2.0]);
        t.push("cd", vec![f64::INFINITY, 24.4, f64::NAN]);
        let mut buf = Vec::new();
        t.write_csv(&mut buf).unwrap();
        assert_eq!(String::from_utf8(buf).unwrap(), "re_p,cd\n0,\n1,24.4\n2,\n");
    }

    #[test]
    fn csv_round_trip_and_errors() {
        let t = Table::read_csv("re_p, x\n1,2\n3.5,4e-3\n".as_bytes(), "t").unwrap();
        assert_eq!(t.get("re_p"), Some(&[1.0, 3.5][..]));
        let mut buf = Vec::new();
        t.write_csv(&mut buf).unwrap();
        let back = Table::read_csv(buf.as_slice(), "b").unwrap();
        assert_eq!(back, t);
        let e = Table::read_csv("a\nfoo\n".as_bytes(), "in.csv").unwrap_err();
        assert!(format!("{e:#}").contains("`foo` is not a number"));
        let e = Table::read_csv("a\nNaN\n".as_bytes(), "in.csv").unwrap_err();
        assert!(format!("{e:#}").contains("not a finite number"));
    }
}
