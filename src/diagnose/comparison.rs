//! One closure prediction held against one measured field: the cells used, the two
//! values side by side, their RMS difference; written as CSV and drawn against z.

use std::path::{Path, PathBuf};

use anyhow::Context;

use saltus_solvers::Profiles;

use crate::figures::profiles::{draw_profiles, Panel, Reference, SeriesLabelPosition};
use crate::table::Table;

/// A closure's prediction of one quantity against its measured value, over the usable
/// cells of a run.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// label of the closure (its table's name, or its model name)
    pub closure: String,
    /// what is compared, e.g. `mu(I)`, `g0 carnahan_starling`
    pub quantity: &'static str,
    /// unit of the quantity (the figure's axis)
    pub unit: &'static str,
    /// name of the control number of the `x` column (`I`, `K`, `phi`)
    pub control: &'static str,
    /// heights of the cells used (m)
    pub z: Vec<f64>,
    /// control number of each cell
    pub x: Vec<f64>,
    /// measured value of each cell
    pub measured: Vec<f64>,
    /// predicted value of each cell
    pub predicted: Vec<f64>,
    /// further columns of the CSV (e.g. I and J beside K)
    pub extra: Vec<(&'static str, Vec<f64>)>,
}

impl Comparison {
    /// An empty comparison of `quantity` (unit `unit`) against control number `control`.
    pub fn new(closure: &str, quantity: &'static str, unit: &'static str, control: &'static str) -> Self {
        Comparison {
            closure: closure.to_string(),
            quantity,
            unit,
            control,
            z: Vec::new(),
            x: Vec::new(),
            measured: Vec::new(),
            predicted: Vec::new(),
            extra: Vec::new(),
        }
    }

    /// Add one cell if its four numbers are finite (a prediction that diverges, e.g. at
    /// phi_max, is no number to compare); returns whether it was added.
    pub fn push(&mut self, z: f64, x: f64, measured: f64, predicted: f64) -> bool {
        if ![z, x, measured, predicted].iter().all(|v| v.is_finite()) {
            return false;
        }
        self.z.push(z);
        self.x.push(x);
        self.measured.push(measured);
        self.predicted.push(predicted);
        true
    }

    /// Add the cells of `other` (the same comparison on another run) after these; the
    /// extra columns are kept where both have them.
    pub fn append(&mut self, other: &Comparison) {
        self.z.extend(&other.z);
        self.x.extend(&other.x);
        self.measured.extend(&other.measured);
        self.predicted.extend(&other.predicted);
        for (name, v) in &mut self.extra {
            match other.extra.iter().find(|(n, _)| n == name) {
                Some((_, w)) => v.extend(w),
                None => v.resize(self.z.len(), f64::NAN),
            }
        }
    }

    /// Number of cells compared.
    pub fn cells(&self) -> usize {
        self.z.len()
    }

    /// RMS difference sqrt(mean((predicted - measured)^2)); NaN without cells.
    pub fn rms(&self) -> f64 {
        let n = self.cells();
        if n == 0 {
            return f64::NAN;
        }
        let s: f64 = self.predicted.iter().zip(&self.measured).map(|(p, m)| (p - m) * (p - m)).sum();
        (s / n as f64).sqrt()
    }

    /// RMS difference over the RMS of the measured values; NaN without cells or when the
    /// measured values all vanish.
    pub fn relative_rms(&self) -> f64 {
        let n = self.cells() as f64;
        let scale = (self.measured.iter().map(|m| m * m).sum::<f64>() / n).sqrt();
        if scale > 0.0 {
            self.rms() / scale
        } else {
            f64::NAN
        }
    }

    /// Mean of (predicted - measured) over the measured RMS: the sign says whether the
    /// closure over- (> 0) or under-predicts.
    pub fn relative_bias(&self) -> f64 {
        let n = self.cells() as f64;
        let scale = (self.measured.iter().map(|m| m * m).sum::<f64>() / n).sqrt();
        let bias = self.predicted.iter().zip(&self.measured).map(|(p, m)| p - m).sum::<f64>() / n;
        if scale > 0.0 {
            bias / scale
        } else {
            f64::NAN
        }
    }

    /// The cells as a table: z, the control number, measured, predicted, the extra columns.
    pub fn table(&self) -> Table {
        let mut t = Table::default();
        t.push("z", self.z.clone());
        t.push(self.control, self.x.clone());
        t.push("measured", self.measured.clone());
        t.push("predicted", self.predicted.clone());
        for (name, v) in &self.extra {
            t.push(*name, v.clone());
        }
        t
    }

    /// File stem of this comparison: closure and quantity in lower case, `-` between words.
    pub fn stem(&self) -> String {
        crate::compare::slug(&format!("{} {}", self.closure, self.quantity))
    }

    /// Write `<stem>.csv` and `<stem>.png` (measured as symbols, predicted as a line,
    /// against z) into `dir`; returns the two paths.
    pub fn write(&self, dir: &Path) -> anyhow::Result<[PathBuf; 2]> {
        let csv = dir.join(format!("{}.csv", self.stem()));
        self.table().write_csv_file(&csv)?;
        let png = dir.join(format!("{}.png", self.stem()));
        let context = || format!("{}: cannot draw", png.display());
        // one column name for both, so that the measured symbols overlay the line
        let mut line = Profiles::default();
        line.push("z", self.z.clone());
        line.push("predicted", self.predicted.clone());
        let mut marks = Table::default();
        marks.push("z", self.z.clone());
        marks.push("predicted", self.measured.clone());
        let panel = Panel {
            title: self.quantity,
            x_desc: self.unit,
            columns: &["predicted"],
            log_x: false,
            legend: SeriesLabelPosition::UpperRight,
        };
        let title = format!("{}: {} (relative RMS {})", self.closure, self.quantity, figure(self.relative_rms()));
        draw_profiles(
            &title,
            &[panel],
            &[("predicted".into(), &line)],
            &[Reference { label: "measured", table: &marks }],
            &png,
        )
        .with_context(context)?;
        Ok([csv, png])
    }
}

/// A number for the table: 4 significant digits, `-` when undefined.
pub fn figure(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.4e}")
    } else {
        "-".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rms_of_known_differences() {
        let mut c = Comparison::new("m", "mu(I)", "-", "I");
        c.push(0.0, 0.1, 1.0, 1.1);
        c.push(1.0, 0.2, 1.0, 0.9);
        assert!((c.rms() - 0.1).abs() < 1e-15);
        assert!((c.relative_rms() - 0.1).abs() < 1e-15);
        assert!(c.relative_bias().abs() < 1e-15);
        let mut empty = Comparison::new("m", "mu(I)", "-", "I");
        assert!(!empty.push(0.0, 0.1, 1.0, f64::INFINITY));
        assert!(empty.rms().is_nan() && empty.relative_rms().is_nan());
    }
}
