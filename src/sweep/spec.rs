//! The sweep file: a base scene, named axes, their product or zip, per-point overrides;
//! read, checked and expanded into one resolved scene per point before any run.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use saltus_core::scene::{apply_override, parse_table, Meta, Scene};
use saltus_core::Error;
use serde::Deserialize;

use crate::study_file::{self, key_error};

/// Most points of one sweep: past any study a machine or a job array runs, small enough
/// that a typo in a `logspace` count is refused rather than expanded.
pub const MAX_POINTS: usize = 100_000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    base: String,
    #[serde(default)]
    meta: Meta,
    #[serde(default)]
    combine: Combine,
    #[serde(default)]
    set: Vec<String>,
    #[serde(default)]
    unset: Vec<String>,
    #[serde(default, rename = "axis")]
    axes: Vec<RawAxis>,
    #[serde(default, rename = "point")]
    points: Vec<RawPoint>,
    #[serde(default)]
    jobs: Option<usize>,
    #[serde(default)]
    warm_start: bool,
    #[serde(default)]
    figure: Option<FigureSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    key: String,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    values: Option<Vec<toml::Value>>,
    #[serde(default)]
    linspace: Option<(f64, f64, usize)>,
    #[serde(default)]
    logspace: Option<(f64, f64, usize)>,
    #[serde(default)]
    labels: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoint {
    #[serde(rename = "where")]
    at: toml::Table,
    #[serde(default)]
    set: Vec<String>,
    #[serde(default)]
    unset: Vec<String>,
}

/// How the axes make points.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// every combination of the axes' values, the last axis fastest
    #[default]
    Product,
    /// the i-th value of every axis together (axes of equal length)
    Zip,
}

/// `[figure]`: what the study's figure draws.
#[derive(Clone, Debug, Default, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct FigureSpec {
    /// name of the axis on x (default: the first numeric axis)
    #[serde(default)]
    pub x: Option<String>,
    /// summary field on y (default `qs_star`)
    #[serde(default)]
    pub y: Option<String>,
    /// summary field on x instead of the axis (e.g. `shields_turbulent`)
    #[serde(default)]
    pub x_field: Option<String>,
    /// only points with y above this enter the 3/2-law fit (default 1e-3)
    #[serde(default)]
    pub fit_min: Option<f64>,
    /// the Meyer-Peter & Mueller flume data (CSV with `Shields stress` and
    /// `dimensionless bedload flux per unit width`), relative to the sweep file; drawn
    /// when present
    #[serde(default)]
    pub data: Option<String>,
}

/// One axis: a scene key and its values.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Axis {
    /// scene key, as in `--set`
    pub key: String,
    /// column name in the table (default: the key)
    pub name: String,
    /// its values
    pub values: Vec<toml::Value>,
    /// one label per value (default: the value as TOML)
    pub labels: Vec<String>,
}

/// One point of a sweep: its index, the value of every axis and its overrides.
#[derive(Clone, Debug)]
pub struct Point {
    /// position in the sweep, from 0
    pub index: usize,
    /// per axis, the index of its value
    pub at: Vec<usize>,
    /// `KEY=VALUE` overrides, the command line's, the sweep's then the axes'
    pub set: Vec<String>,
    /// keys of the base removed before the overrides (the sweep's `unset`)
    pub unset: Vec<String>,
    /// keys removed after the overrides (the point's own `unset`), before its own `set`
    pub own_unset: Vec<String>,
    /// the point's own overrides, last
    pub own_set: Vec<String>,
}

impl Point {
    /// Output folder name of the point inside the sweep's folder.
    pub fn dir_name(&self) -> String {
        format!("point_{:04}", self.index)
    }
}

/// A loaded sweep: every point expanded and its scene resolved.
#[derive(Debug)]
pub struct Sweep {
    /// the sweep file
    pub file: PathBuf,
    /// the base scene file
    pub base: PathBuf,
    /// name (the file stem when not given) and description
    pub meta: Meta,
    /// product or zip
    pub combine: Combine,
    /// the axes, in file order
    pub axes: Vec<Axis>,
    /// the points, in order
    pub points: Vec<Point>,
    /// points run at once (default: the cores)
    pub jobs: Option<usize>,
    /// start each Eulerian point from its nearest finished neighbour's steady state
    pub warm_start: bool,
    /// the figure
    pub figure: FigureSpec,
}

/// The raw table of the scene file `file`, before any override.
fn scene_table(file: &Path) -> anyhow::Result<toml::Table> {
    let text = std::fs::read_to_string(file).map_err(|source| Error::Io { file: file.to_path_buf(), source })?;
    Ok(parse_table(&text, file)?)
}

fn label(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(f) => format!("{f}"),
        other => other.to_string(),
    }
}

fn spaced(file: &Path, key: &str, (a, b, n): (f64, f64, usize), log: bool) -> anyhow::Result<Vec<toml::Value>> {
    if !(a.is_finite() && b.is_finite()) {
        return Err(key_error(file, key, format!("[{a}, {b}, {n}]: the ends must be finite numbers")));
    }
    if log && !(a > 0.0 && b > 0.0) {
        return Err(key_error(file, key, format!("[{a}, {b}, {n}]: the ends of a logspace must be > 0")));
    }
    if n == 0 || n > MAX_POINTS {
        return Err(key_error(file, key, format!("[{a}, {b}, {n}]: the count must be in [1, {MAX_POINTS}]")));
    }
    let (a, b) = if log { (a.ln(), b.ln()) } else { (a, b) };
    Ok((0..n)
        .map(|i| {
            // the ends exactly as given, the inside evenly between them
            let t = if n == 1 { 0.0 } else { i as f64 / (n - 1) as f64 };
            let x = if i + 1 == n && n > 1 { b } else { a + (b - a) * t };
            toml::Value::Float(if log { x.exp() } else { x })
        })
        .collect())
}

fn finite_value(v: &toml::Value) -> bool {
    match v {
        toml::Value::Float(f) => f.is_finite(),
        toml::Value::Array(a) => a.iter().all(finite_value),
        toml::Value::Table(t) => t.values().all(finite_value),
        _ => true,
    }
}

/// `value` as a number, for an axis on a figure or a `where` match.
pub fn as_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn same_value(a: &toml::Value, b: &toml::Value) -> bool {
    match (as_number(a), as_number(b)) {
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()),
        _ => a == b,
    }
}

/// Remove `key` (dotted) from a raw scene table; `Err` when it is not there.
fn remove_key(table: &mut toml::Table, key: &str) -> Result<(), String> {
    let parts: Vec<&str> = key.split('.').collect();
    let mut cur = table;
    for p in &parts[..parts.len() - 1] {
        cur = cur
            .get_mut(*p)
            .and_then(|v| v.as_table_mut())
            .ok_or_else(|| format!("`{key}` is not in the base scene"))?;
    }
    cur.remove(parts[parts.len() - 1]).map(|_| ()).ok_or_else(|| format!("`{key}` is not in the base scene"))
}

/// Whether a scene error `msg` is about `key`: it names the key, or the table holding it
/// and its last segment (an unknown field).
fn blames(msg: &str, key: &str) -> bool {
    if msg.contains(&format!("`{key}`")) {
        return true;
    }
    match key.rsplit_once('.') {
        Some((table, last)) => msg.contains(&format!("`{table}`")) && msg.contains(&format!("`{last}`")),
        None => msg.contains(&format!("`{key}`")),
    }
}

fn has_key(t: &toml::Table, key: &str) -> bool {
    let mut cur = Some(t);
    let parts: Vec<&str> = key.split('.').collect();
    for p in &parts[..parts.len() - 1] {
        cur = cur.and_then(|t| t.get(*p)).and_then(|v| v.as_table());
    }
    cur.is_some_and(|t| t.contains_key(parts[parts.len() - 1]))
}

impl Axis {
    /// The `KEY=VALUE` override of value `i`.
    pub fn set(&self, i: usize) -> String {
        format!("{}={}", self.key, self.values[i])
    }

    /// Value `i` as a number, when it is one.
    pub fn number(&self, i: usize) -> Option<f64> {
        as_number(&self.values[i])
    }

    /// Whether it is the seed of an ensemble.
    pub fn is_seed(&self) -> bool {
        self.key == "seed"
    }
}

/// Read and check a sweep file: its keys, its axes, its points, and every point's scene
/// (resolved and checked as `saltus check` would), so that bad input is refused before
/// any run. `set` are the command line's overrides, applied to every point first.
pub fn load(path: &Path, set: &[String]) -> anyhow::Result<Sweep> {
    let (raw, _): (RawFile, _) = study_file::read(path)?;
    if raw.axes.is_empty() {
        return Err(key_error(path, "axis", "no [[axis]] table; give at least one, each with key and values"));
    }
    if raw.jobs == Some(0) {
        return Err(key_error(path, "jobs", "0: give the number of points run at once, at least 1"));
    }
    let mut axes = Vec::with_capacity(raw.axes.len());
    let mut names = HashSet::new();
    for (i, a) in raw.axes.into_iter().enumerate() {
        let at = |k: &str| format!("axis[{i}].{k}");
        if a.key.trim().is_empty() || a.key.split('.').any(|p| p.trim().is_empty()) {
            return Err(key_error(path, at("key"), format!("`{}`: a scene key such as physics.shields", a.key)));
        }
        let values = match (a.values, a.linspace, a.logspace) {
            (Some(v), None, None) => v,
            (None, Some(l), None) => spaced(path, &at("linspace"), l, false)?,
            (None, None, Some(l)) => spaced(path, &at("logspace"), l, true)?,
            _ => return Err(key_error(
                path,
                format!("axis[{i}]"),
                "give exactly one of values = [...], linspace = [start, stop, count], logspace = [start, stop, count]",
            )),
        };
        if values.is_empty() {
            return Err(key_error(path, at("values"), "empty: give at least one value"));
        }
        if let Some(k) = values.iter().position(|v| !finite_value(v)) {
            return Err(key_error(
                path,
                format!("axis[{i}].values[{k}]"),
                format!("{}: not a finite number", values[k]),
            ));
        }
        let labels = match a.labels {
            Some(l) if l.len() != values.len() => {
                return Err(key_error(
                    path,
                    at("labels"),
                    format!("{} labels for {} values: give one per value", l.len(), values.len()),
                ))
            }
            Some(l) => l,
            None => values.iter().map(label).collect(),
        };
        let name = a.name.unwrap_or_else(|| a.key.clone());
        if !names.insert(name.clone()) {
            return Err(key_error(path, at("name"), format!("`{name}` names an earlier axis too")));
        }
        axes.push(Axis { key: a.key, name, values, labels });
    }
    if raw.combine == Combine::Zip {
        let n = axes[0].values.len();
        if let Some((i, a)) = axes.iter().enumerate().find(|(_, a)| a.values.len() != n) {
            return Err(key_error(
                path,
                format!("axis[{i}]"),
                format!(
                    "combine = \"zip\" takes axes of equal length: `{}` has {} values, `{}` has {n}",
                    a.name,
                    a.values.len(),
                    axes[0].name
                ),
            ));
        }
    }
    let at_list: Vec<Vec<usize>> = match raw.combine {
        Combine::Zip => (0..axes[0].values.len()).map(|k| vec![k; axes.len()]).collect(),
        Combine::Product => {
            let total = axes.iter().try_fold(1usize, |n, a| n.checked_mul(a.values.len()).filter(|&n| n <= MAX_POINTS));
            let Some(total) = total else {
                return Err(key_error(
                    path,
                    "axis",
                    format!("the product of the axes makes more than {MAX_POINTS} points"),
                ));
            };
            (0..total)
                .map(|mut k| {
                    let mut at = vec![0; axes.len()];
                    for (j, a) in axes.iter().enumerate().rev() {
                        at[j] = k % a.values.len();
                        k /= a.values.len();
                    }
                    at
                })
                .collect()
        }
    };
    let base = study_file::base_scene(path, &raw.base)?;
    let base_table = scene_table(&base)?;
    for (k, u) in raw.unset.iter().enumerate() {
        let mut t = base_table.clone();
        remove_key(&mut t, u).map_err(|m| key_error(path, format!("unset[{k}]"), m))?;
    }
    // per-point overrides: each `where` names axes by name and matches one value of each
    let mut own: Vec<(Vec<String>, Vec<String>)> = vec![(Vec::new(), Vec::new()); at_list.len()];
    for (p, rp) in raw.points.iter().enumerate() {
        let mut matched = vec![true; at_list.len()];
        if rp.at.is_empty() {
            return Err(key_error(path, format!("point[{p}].where"), "empty: name at least one axis and its value"));
        }
        for (name, value) in &rp.at {
            let Some(j) = axes.iter().position(|a| &a.name == name) else {
                let known: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
                return Err(key_error(
                    path,
                    format!("point[{p}].where.{name}"),
                    format!("no axis is named `{name}`; the axes: {}", known.join(", ")),
                ));
            };
            let Some(k) = axes[j].values.iter().position(|v| same_value(v, value)) else {
                return Err(key_error(
                    path,
                    format!("point[{p}].where.{name}"),
                    format!("{value} is not a value of the axis `{name}`"),
                ));
            };
            for (m, at) in at_list.iter().enumerate() {
                matched[m] &= at[j] == k;
            }
        }
        if !matched.iter().any(|&m| m) {
            return Err(key_error(path, format!("point[{p}].where"), "matches no point of the sweep"));
        }
        for (m, yes) in matched.into_iter().enumerate() {
            if yes {
                own[m].0.extend(rp.set.iter().cloned());
                own[m].1.extend(rp.unset.iter().cloned());
            }
        }
    }
    let points: Vec<Point> = at_list
        .into_iter()
        .zip(own)
        .enumerate()
        .map(|(index, (at, (pset, punset)))| {
            let mut s: Vec<String> = set.iter().chain(&raw.set).cloned().collect();
            s.extend(axes.iter().zip(&at).map(|(a, &k)| a.set(k)));
            Point { index, at, set: s, unset: raw.unset.clone(), own_unset: punset, own_set: pset }
        })
        .collect();
    let meta = study_file::named(raw.meta, path, "sweep");
    let sweep = Sweep {
        file: path.to_path_buf(),
        base,
        meta,
        combine: raw.combine,
        axes,
        points,
        jobs: raw.jobs,
        warm_start: raw.warm_start,
        figure: raw.figure.unwrap_or_default(),
    };
    // every point's scene, resolved and checked, before any run
    for p in &sweep.points {
        sweep.scene(p, &base_table)?;
    }
    Ok(sweep)
}

impl Sweep {
    /// The raw table of the base scene.
    pub fn base_table(&self) -> anyhow::Result<toml::Table> {
        scene_table(&self.base)
    }

    /// The resolved and checked scene of `p`, built on `base` (the raw base scene).
    /// Errors name the sweep file, the point and the axis or override at fault.
    pub fn scene(&self, p: &Point, base: &toml::Table) -> anyhow::Result<Scene> {
        let file = &self.file;
        let mut t = base.clone();
        for u in &p.unset {
            // each is in the base: checked at load
            let _ = remove_key(&mut t, u);
        }
        let set = |t: &mut toml::Table, list: &[String]| {
            list.iter().try_for_each(|o| {
                apply_override(t, o).map_err(|e| anyhow::anyhow!("{}: point {}: {e}", file.display(), p.index))
            })
        };
        set(&mut t, &p.set)?;
        for (k, u) in p.own_unset.iter().enumerate() {
            remove_key(&mut t, u).map_err(|m| {
                key_error(file, format!("point[..].unset[{k}]"), format!("point {}: {m} nor set by the sweep", p.index))
            })?;
        }
        set(&mut t, &p.own_set)?;
        let mut scene = Scene::from_table(t, &self.base).map_err(|e| {
            // name the axis whose key the scene refuses, when it is one
            let msg = e.to_string();
            let axis = self.axes.iter().enumerate().find(|(_, a)| blames(&msg, &a.key));
            match axis {
                Some((i, a)) => key_error(
                    file,
                    format!("axis[{i}].key"),
                    format!("`{}` = {} (point {}): {msg}", a.key, a.values[p.at[i]], p.index),
                ),
                None => anyhow::anyhow!("{}: point {} ({}): {msg}", file.display(), p.index, self.describe(p)),
            }
        })?;
        let resolved: toml::Table = scene.to_toml()?.parse()?;
        for (i, a) in self.axes.iter().enumerate() {
            if !a.is_seed() && !has_key(&resolved, &a.key) {
                return Err(key_error(
                    file,
                    format!("axis[{i}].key"),
                    format!(
                        "`{}` is not a key of the scene (see `saltus check {}` for its keys)",
                        a.key,
                        self.base.display()
                    ),
                ));
            }
        }
        saltus_solvers::validate(&scene)
            .map_err(|e| anyhow::anyhow!("{}: point {} ({}): {e}", file.display(), p.index, self.describe(p)))?;
        scene.meta.name = format!("{} [{}]", scene.meta.name, self.describe(p));
        Ok(scene)
    }

    /// `name = label` of every axis at `p`.
    pub fn describe(&self, p: &Point) -> String {
        self.axes
            .iter()
            .zip(&p.at)
            .map(|(a, &k)| format!("{} = {}", a.name, a.labels[k]))
            .collect::<Vec<_>>()
            .join(", ")
    }
}
