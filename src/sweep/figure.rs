//! The study's figure ([`crate::figures::transport`]): qs* against the swept Shields
//! number, log-log, with the 3/2-law fit, the classic bedload laws
//! ([`saltus_solvers::measures::bedload::CLASSIC`]) and, when present, the Meyer-Peter & Mueller
//! (1948) flume data as compiled by Recking (2010).

use std::path::Path;

use anyhow::{bail, Context};
use saltus_solvers::measures::bedload::TransportLaw;

use super::fit::Fit;
use super::series::Series;
use crate::figures::transport::{self, Data};

/// File name of the figure in the sweep's folder.
pub const FIGURE: &str = "sweep.png";

/// Legend label of the flume data.
const MPM_DATA: &str = "Meyer-Peter & Mueller 1948 flume data (Recking 2010)";

/// Read the flume data: (Shields stress, dimensionless bedload flux) of each row.
pub fn read_mpm(path: &Path) -> anyhow::Result<Vec<(f64, f64)>> {
    let mut r = csv::Reader::from_path(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let header = r.headers()?.clone();
    let col = |name: &str| header.iter().position(|h| h.trim() == name);
    let (Some(x), Some(y)) = (col("Shields stress"), col("dimensionless bedload flux per unit width")) else {
        bail!("{}: no `Shields stress` and `dimensionless bedload flux per unit width` columns", path.display());
    };
    let mut out = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let rec = rec.with_context(|| format!("{}: row {}", path.display(), i + 2))?;
        let num = |k: usize| rec.get(k).and_then(|c| c.trim().parse::<f64>().ok()).filter(|v| v.is_finite());
        if let (Some(a), Some(b)) = (num(x), num(y)) {
            out.push((a, b));
        }
    }
    Ok(out)
}

/// Draw each series (with error bars) with its fit, the `laws` and the flume `data` into
/// `png`.
#[allow(clippy::too_many_arguments)]
pub fn draw(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    fits: &[(String, Fit)],
    laws: &[TransportLaw],
    data: &[(f64, f64)],
    png: &Path,
) -> anyhow::Result<()> {
    let drawn: Vec<transport::Series> = series
        .iter()
        .map(|s| {
            let name = if s.label.is_empty() { "this sweep".to_string() } else { s.label.clone() };
            let fit = fits.iter().find(|(l, _)| l == &s.label).map(|(_, f)| {
                let bound = if f.at_bound { ", theta_c at the smallest theta" } else { "" };
                let label = format!(
                    "{name}: {:.3} (+- {:.2}) (theta - {:.4} (+- {:.4}))^1.5, {} points{bound}",
                    f.a, f.a_stderr, f.theta_c, f.theta_c_stderr, f.n
                );
                (label, TransportLaw { name: "", source: "", a: f.a, theta_c: f.theta_c })
            });
            transport::Series { label: name, marks: &s.marks, fit }
        })
        .collect();
    transport::draw(title, (x_desc, y_desc), &drawn, laws, Data { label: MPM_DATA, points: data }, png)
}
