//! The figure's series: y (qs* by default) against the swept number, one series per
//! value of the other axes (a seed axis pooled), and their 3/2-law fits as a table.

use std::path::Path;

use super::fit::Fit;
use super::manifest::{Manifest, Status};
use super::spec::Sweep;
use super::table::{self, Fields};

/// File name of the fits in the sweep's folder.
pub const FITS: &str = "sweep_fit.csv";

/// One point of a series: x, y, the error of y.
pub type Mark = (f64, f64, Option<f64>);

/// The points that share the values of every axis but x and the seed.
#[derive(Clone, Debug)]
pub struct Series {
    /// `name = label` of those axes (empty when there are none)
    pub label: String,
    /// its points, in sweep order
    pub marks: Vec<Mark>,
}

/// The series of the figure: x from the axis (or the summary field) the figure names, y
/// the summary field of every done point, pooled over the seeds of an ensemble, with its
/// error: the run's own (`<y>_stderr`) or, pooled, the larger of the spread across seeds
/// and the pooled run errors. `None` without a numeric axis. Returns the x and y names.
pub fn of(sweep: &Sweep, m: &Manifest, summaries: &[Option<Fields>]) -> Option<(String, String, Vec<Series>)> {
    let y = sweep.figure.y.clone().unwrap_or_else(|| "qs_star".into());
    let axis = match &sweep.figure.x {
        Some(name) => sweep.axes.iter().position(|a| &a.name == name)?,
        None => sweep.axes.iter().position(|a| !a.is_seed() && (0..a.values.len()).all(|k| a.number(k).is_some()))?,
    };
    let x_of = |i: usize| -> Option<f64> {
        match &sweep.figure.x_field {
            Some(f) => summaries[i].as_ref()?.number(f),
            None => sweep.axes[axis].number(sweep.points[i].at[axis]),
        }
    };
    let err_key = format!("{y}_stderr");
    let done = |i: usize| m.points[i].status == Status::Done;
    // points with the same values of every axis but the seed make one mark
    let mut groups: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
    for (i, p) in sweep.points.iter().enumerate() {
        let key: Vec<usize> =
            p.at.iter().enumerate().map(|(j, &k)| if sweep.axes[j].is_seed() { 0 } else { k }).collect();
        match groups.iter_mut().find(|g| g.0 == key) {
            Some(g) => g.1.push(i),
            None => groups.push((key, vec![i])),
        }
    }
    let mut series: Vec<(Vec<usize>, Series)> = Vec::new();
    for (key, pts) in groups {
        let pts: Vec<usize> = pts.into_iter().filter(|&i| done(i)).collect();
        let xs: Vec<f64> = pts.iter().filter_map(|&i| x_of(i)).collect();
        let ys: Vec<f64> = pts.iter().filter_map(|&i| summaries[i].as_ref()?.number(&y)).collect();
        let es: Vec<f64> = pts.iter().filter_map(|&i| summaries[i].as_ref()?.number(&err_key)).collect();
        let (Some(px), Some(py)) = (table::pool(&xs), table::pool(&ys)) else { continue };
        let e = match (py.sem, table::pool_errors(&es)) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        // the series: every axis but x and the seed
        let skey: Vec<usize> = key.iter().enumerate().map(|(j, &k)| if j == axis { 0 } else { k }).collect();
        let mark = (px.mean, py.mean, e);
        match series.iter_mut().find(|s| s.0 == skey) {
            Some(s) => s.1.marks.push(mark),
            None => {
                let label = sweep
                    .axes
                    .iter()
                    .enumerate()
                    .filter(|(j, a)| *j != axis && !a.is_seed())
                    .map(|(j, a)| format!("{} = {}", a.name, a.labels[key[j]]))
                    .collect::<Vec<_>>()
                    .join(", ");
                series.push((skey, Series { label, marks: vec![mark] }));
            }
        }
    }
    let x_desc = sweep.figure.x_field.clone().unwrap_or_else(|| sweep.axes[axis].name.clone());
    Some((x_desc, y, series.into_iter().map(|s| s.1).collect()))
}

/// Write the fits, one row per series:
/// `series,n,a,a_stderr,theta_c,theta_c_stderr,rms,at_bound,n_stand_in`.
pub fn write_fits(path: &Path, fits: &[(String, Fit)]) -> anyhow::Result<()> {
    let header: Vec<String> =
        ["series", "n", "a", "a_stderr", "theta_c", "theta_c_stderr", "rms", "at_bound", "n_stand_in"]
            .map(String::from)
            .to_vec();
    let rows: Vec<Vec<String>> = fits
        .iter()
        .map(|(label, f)| {
            vec![
                label.clone(),
                f.n.to_string(),
                format!("{:?}", f.a),
                format!("{:?}", f.a_stderr),
                format!("{:?}", f.theta_c),
                format!("{:?}", f.theta_c_stderr),
                format!("{:?}", f.rms),
                f.at_bound.to_string(),
                f.n_stand_in.to_string(),
            ]
        })
        .collect();
    table::write_csv(path, &header, &rows)
}
