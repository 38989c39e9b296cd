//! `sweep.csv`: one row per point, the axes' values then every field of its
//! `summary.json` (the statistical errors of a DEM run among them); and, for a sweep with
//! a `seed` axis, `sweep_seeds.csv`: one row per point of the other axes, its seeds
//! pooled (mean, standard error across seeds beside the runs' own block errors).

use std::path::Path;

use anyhow::Context;
use serde::de::{MapAccess, Visitor};
use serde::Deserialize;
use serde_json::Value;

use super::manifest::{Manifest, Status};

/// File names in the sweep's folder.
pub const TABLE: &str = "sweep.csv";
/// See [`TABLE`].
pub const SEEDS: &str = "sweep_seeds.csv";

/// The fields of a JSON object in the order they are written (serde_json's own map
/// sorts them unless a feature changes every map of the workspace).
#[derive(Clone, Debug, Default)]
pub struct Fields(pub Vec<(String, Value)>);

impl<'de> Deserialize<'de> for Fields {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Fields;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Fields, A::Error> {
                let mut out = Vec::new();
                while let Some((k, v)) = m.next_entry::<String, Value>()? {
                    out.push((k, v));
                }
                Ok(Fields(out))
            }
        }
        de.deserialize_map(V)
    }
}

impl Fields {
    /// Field `name` as a number.
    pub fn number(&self, name: &str) -> Option<f64> {
        self.0.iter().find(|(k, _)| k == name).and_then(|(_, v)| v.as_f64()).filter(|v| v.is_finite())
    }

    /// Field `name` as text.
    pub fn text(&self, name: &str) -> Option<&str> {
        self.0.iter().find(|(k, _)| k == name).and_then(|(_, v)| v.as_str())
    }
}

/// Read a point's `summary.json`; `None` when it has none (not run yet).
pub fn read_summary(dir: &Path) -> anyhow::Result<Option<Fields>> {
    crate::run_files::summary(dir)
}

/// The status a point's summary says it ended with.
pub fn status_of(s: &Fields) -> Status {
    match s.text("ending") {
        Some("steady" | "end_time" | "max_steps") => Status::Done,
        Some("unstable") => Status::Unstable,
        Some("interrupted") => Status::Interrupted,
        _ => Status::Failed,
    }
}

fn cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        // as written in summary.json: integers as integers, floats to their last digit
        Value::Number(n) => n.to_string(),
        other => other.to_string(),
    }
}

/// Fields of every summary, in the order of their first appearance.
fn columns(summaries: &[Option<Fields>]) -> Vec<String> {
    let mut cols: Vec<String> = Vec::new();
    for s in summaries.iter().flatten() {
        for (k, _) in &s.0 {
            if !cols.contains(k) {
                cols.push(k.clone());
            }
        }
    }
    cols
}

/// The manifest's columns of `sweep.csv`, after the axes: the point's cost counts every run
/// of it (a resumed point's earlier runs too), so the summary's fields of these names,
/// which count its last run, are not repeated.
const MANIFEST_COLUMNS: [&str; 5] = ["status", "wall_time_s", "cpu_time_s", "warm_start_from", "warm_start_refused"];

/// Header and rows of `sweep.csv` for `manifest` with the points' summaries.
pub fn rows(manifest: &Manifest, summaries: &[Option<Fields>]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut cols = columns(summaries);
    cols.retain(|c| !MANIFEST_COLUMNS.contains(&c.as_str()));
    let mut header = vec!["point".to_string(), "dir".into()];
    header.extend(manifest.axes.iter().map(|a| a.name.clone()));
    header.extend(MANIFEST_COLUMNS.iter().map(|c| c.to_string()));
    header.extend(cols.iter().map(|c| if c == "error" { "run_error".into() } else { c.clone() }));
    let rows = manifest
        .points
        .iter()
        .zip(summaries)
        .map(|(p, s)| {
            let mut row = vec![p.index.to_string(), p.dir.clone()];
            for a in &manifest.axes {
                let k = a.values.iter().position(|v| Some(v) == p.values.get(&a.name));
                row.push(k.map_or_else(String::new, |k| a.labels[k].clone()));
            }
            row.push(serde_json::to_value(p.status).ok().as_ref().map(cell).unwrap_or_default());
            row.push(p.wall_time_s.map_or_else(String::new, |c| format!("{c:?}")));
            row.push(p.cpu_time_s.map_or_else(String::new, |c| format!("{c:?}")));
            row.push(p.warm_start_from.clone().unwrap_or_default());
            row.push(p.warm_start_refused.clone().unwrap_or_default());
            for c in &cols {
                let v = s.as_ref().and_then(|s| s.0.iter().find(|(k, _)| k == c)).map(|(_, v)| cell(v));
                row.push(v.unwrap_or_default());
            }
            row
        })
        .collect();
    (header, rows)
}

/// Write `header` and `rows` as CSV to `path`.
pub fn write_csv(path: &Path, header: &[String], rows: &[Vec<String>]) -> anyhow::Result<()> {
    let mut w = csv::Writer::from_path(path).with_context(|| format!("{}: cannot create", path.display()))?;
    w.write_record(header)?;
    for r in rows {
        w.write_record(r)?;
    }
    w.flush().with_context(|| format!("{}: cannot write", path.display()))
}

/// One group of seeds: the other axes' value indices and the points in it.
#[derive(Clone, Debug)]
pub struct SeedGroup {
    /// per non-seed axis (in order), the value index
    pub at: Vec<usize>,
    /// the points (indices into the manifest)
    pub points: Vec<usize>,
}

/// Mean and standard error across seeds of a field, with the runs' own errors pooled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pooled {
    /// seeds with the field
    pub n: usize,
    /// mean over them
    pub mean: f64,
    /// standard deviation across seeds over sqrt(n); `None` with one seed
    pub sem: Option<f64>,
}

/// Mean and standard error of `values`.
pub fn pool(values: &[f64]) -> Option<Pooled> {
    let n = values.len();
    if n == 0 {
        return None;
    }
    // shifted by the first value, so that equal values pool to that value and a zero
    // error exactly (the plain sum over n can land an ulp off it)
    let first = values[0];
    let mean = first + values.iter().map(|v| v - first).sum::<f64>() / n as f64;
    let sem = (n > 1).then(|| {
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        (var / n as f64).sqrt()
    });
    Some(Pooled { n, mean, sem })
}

/// The error of the mean of `n` independent runs from each run's own standard error:
/// sqrt(sum se^2) / n.
pub fn pool_errors(errors: &[f64]) -> Option<f64> {
    (!errors.is_empty()).then(|| errors.iter().map(|e| e * e).sum::<f64>().sqrt() / errors.len() as f64)
}

/// The points of `manifest` grouped by the value of every axis but the seed.
pub fn seed_groups(manifest: &Manifest) -> Option<Vec<SeedGroup>> {
    let seed = manifest.axes.iter().position(|a| a.key == "seed")?;
    let mut groups: Vec<SeedGroup> = Vec::new();
    for (i, p) in manifest.points.iter().enumerate() {
        let at: Vec<usize> = manifest
            .axes
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != seed)
            .map(|(_, a)| a.values.iter().position(|v| Some(v) == p.values.get(&a.name)).unwrap_or(0))
            .collect();
        match groups.iter_mut().find(|g| g.at == at) {
            Some(g) => g.points.push(i),
            None => groups.push(SeedGroup { at, points: vec![i] }),
        }
    }
    Some(groups)
}

/// Header and rows of `sweep_seeds.csv`: per group, the seeds that finished, and for
/// every numeric field its mean and standard error across seeds (`<field>_seed_sem`);
/// a run's own error (`<field>_stderr`) becomes the error of the mean it pools.
pub fn seed_rows(manifest: &Manifest, summaries: &[Option<Fields>]) -> Option<(Vec<String>, Vec<Vec<String>>)> {
    let groups = seed_groups(manifest)?;
    let cols: Vec<String> = columns(summaries)
        .into_iter()
        .filter(|c| summaries.iter().flatten().any(|s| s.0.iter().any(|(k, v)| k == c && v.is_number())))
        .collect();
    let axes: Vec<_> = manifest.axes.iter().filter(|a| a.key != "seed").collect();
    let mut header: Vec<String> = axes.iter().map(|a| a.name.clone()).collect();
    header.push("seeds".into());
    for c in &cols {
        if c.ends_with("_stderr") {
            header.push(c.clone());
        } else {
            header.push(c.clone());
            header.push(format!("{c}_seed_sem"));
        }
    }
    let rows = groups
        .iter()
        .map(|g| {
            let done: Vec<&Fields> = g
                .points
                .iter()
                .filter(|&&i| manifest.points[i].status == Status::Done)
                .filter_map(|&i| summaries[i].as_ref())
                .collect();
            let mut row: Vec<String> = axes.iter().zip(&g.at).map(|(a, &k)| a.labels[k].clone()).collect();
            row.push(done.len().to_string());
            for c in &cols {
                let vals: Vec<f64> = done.iter().filter_map(|s| s.number(c)).collect();
                if c.ends_with("_stderr") {
                    row.push(pool_errors(&vals).map_or_else(String::new, |e| format!("{e:?}")));
                } else {
                    let p = pool(&vals);
                    row.push(p.map_or_else(String::new, |p| format!("{:?}", p.mean)));
                    row.push(p.and_then(|p| p.sem).map_or_else(String::new, |e| format!("{e:?}")));
                }
            }
            row
        })
        .collect();
    Some((header, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fields_keep_the_order_they_are_written_in() {
        let f: Fields = serde_json::from_str(r#"{"solver": "eulerian", "qs_star": 1.5, "a": null}"#).unwrap();
        let keys: Vec<&str> = f.0.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["solver", "qs_star", "a"]);
        assert_eq!(f.number("qs_star"), Some(1.5));
    }

    /// The mean of n runs each of error e has error e / sqrt(n); across seeds the standard
    /// error is the sample standard deviation over sqrt(n).
    #[test]
    fn pooled_errors_follow_the_error_of_a_mean() {
        let e = pool_errors(&[0.2, 0.2, 0.2, 0.2]).unwrap();
        assert!((e - 0.1).abs() < 1e-15);
        let x = 2.5317272746920922;
        let p = pool(&[x, x, x]).unwrap();
        assert_eq!((p.mean, p.sem), (x, Some(0.0)));
        let p = pool(&[1.0, 2.0, 3.0]).unwrap();
        assert_eq!((p.n, p.mean), (3, 2.0));
        assert!((p.sem.unwrap() - 1.0 / 3f64.sqrt()).abs() < 1e-15);
        assert_eq!(pool(&[4.0]).unwrap().sem, None);
    }
}
