//! The files of a calibration: the calibrated closure tables, every run, the summary.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use saltus_core::param::decimal;

use super::model::{term_names, Evaluation, Problem};
use super::{CalibrationReport, CALIBRATED, JSON, TABLE};

fn write(path: PathBuf, text: &str) -> anyhow::Result<PathBuf> {
    std::fs::write(&path, text).with_context(|| format!("{}: cannot write", path.display()))?;
    Ok(path)
}

/// `calibrated.toml`: the closure tables of the families whose constants were fitted, at
/// the optimum, for `saltus run --closures`.
pub fn write_calibrated(
    problem: &Problem,
    optimum: &[f64],
    r: &CalibrationReport,
    out: &Path,
) -> anyhow::Result<PathBuf> {
    let scene = problem.scene_at(optimum)?;
    let resolved = saltus_core::scene::parse_table(&scene.to_toml()?, &problem.cal.base)?;
    let mut families: Vec<&str> = problem.cal.parameters.iter().filter_map(|p| p.key.split('.').nth(1)).collect();
    families.sort_unstable();
    families.dedup();
    let mut closures = toml::Table::new();
    if let Some(toml::Value::Table(all)) = resolved.get("closures") {
        for f in &families {
            if let Some(t) = all.get(*f) {
                closures.insert(f.to_string(), t.clone());
            }
        }
    }
    let mut doc = toml::Table::new();
    doc.insert("closures".into(), toml::Value::Table(closures));
    let mut text = String::new();
    let _ = writeln!(text, "# Closure tables calibrated by `saltus calibrate {}`", problem.cal.file.display());
    let _ = writeln!(text, "# against {} (base scene {}).", reference_words(problem), problem.cal.base.display());
    let _ =
        writeln!(text, "# Load with `saltus run SCENE --closures THIS_FILE`. Fitted constants (optimum +- stderr):");
    for f in &r.fitted {
        let _ = writeln!(
            text,
            "#   {} = {} +- {:.3e} (start {}; bounds [{}, {}])",
            f.key,
            decimal(f.value),
            f.stderr,
            decimal(f.start),
            decimal(f.bounds[0]),
            decimal(f.bounds[1])
        );
    }
    let ratios: Vec<String> = r.optimum_terms.iter().map(|t| format!("{} {:.3}", t.term, t.ratio)).collect();
    let _ = writeln!(text, "# misfit over the reference's scatter at the optimum: {}; {}", ratios.join(", "), r.reason);
    text.push('\n');
    text.push_str(&toml::to_string(&doc).context("the calibrated closure tables")?);
    write(out.join(CALIBRATED), &text)
}

fn reference_words(problem: &Problem) -> String {
    let r = &problem.cal.reference;
    if r.data {
        "the base scene's reference data".into()
    } else {
        let runs: Vec<String> = r.runs.iter().map(|p| p.display().to_string()).collect();
        format!("the runs {}", runs.join(", "))
    }
}

/// `calibration.csv`: every model run, in order.
pub fn write_table(problem: &Problem, log: &[Evaluation], out: &Path) -> anyhow::Result<PathBuf> {
    let path = out.join(TABLE);
    let mut w = csv::Writer::from_path(&path).with_context(|| format!("{}: cannot create", path.display()))?;
    let mut header = vec!["run".to_string(), "purpose".into()];
    header.extend(problem.cal.parameters.iter().map(|p| p.key.clone()));
    header.extend(term_names(&problem.cal).iter().map(|t| format!("ratio_{t}")));
    header.extend(["chi2", "qs_star", "ending", "steps", "cpu_time_s", "error"].map(String::from));
    w.write_record(&header)?;
    let cell = |v: f64| if v.is_finite() { format!("{v:?}") } else { String::new() };
    for (i, e) in log.iter().enumerate() {
        let mut row = vec![i.to_string(), e.purpose.clone()];
        row.extend(e.params.iter().map(|v| cell(*v)));
        row.extend(e.ratios.iter().map(|v| cell(*v)));
        row.push(cell(e.misfit));
        row.push(e.qs_star.map_or_else(String::new, cell));
        row.push(e.ending.clone());
        row.push(e.steps.to_string());
        row.push(cell(e.cpu_time_s));
        row.push(e.error.clone().unwrap_or_default());
        w.write_record(&row)?;
    }
    w.flush().with_context(|| format!("{}: cannot write", path.display()))?;
    Ok(path)
}

/// A finite number, else null: no non-finite number in the JSON.
fn num(v: f64) -> serde_json::Value {
    if v.is_finite() {
        serde_json::json!(v)
    } else {
        serde_json::Value::Null
    }
}

/// `calibration.json`: the optimum with its errors and correlations, the misfit against
/// the reference's scatter at the start and at the optimum, the stopping reason and cost.
pub fn write_json(problem: &Problem, r: &CalibrationReport, out: &Path) -> anyhow::Result<PathBuf> {
    let matrix = |m: &[Vec<f64>]| -> serde_json::Value {
        m.iter().map(|row| row.iter().map(|v| num(*v)).collect::<Vec<_>>()).collect::<Vec<_>>().into()
    };
    let terms = |t: &[super::TermMisfit]| -> serde_json::Value {
        t.iter()
            .map(|m| {
                serde_json::json!({"term": m.term, "difference": num(m.difference), "scatter": num(m.scatter), "ratio": num(m.ratio)})
            })
            .collect::<Vec<_>>()
            .into()
    };
    let fitted: Vec<serde_json::Value> = r
        .fitted
        .iter()
        .zip(&problem.cal.parameters)
        .map(|(f, p)| {
            let profile: Vec<serde_json::Value> = f
                .profile
                .iter()
                .map(|q| serde_json::json!({"value": num(q.value), "delta_chi2": num(q.delta_chi2), "params": q.params.iter().map(|v| num(*v)).collect::<Vec<_>>()}))
                .collect();
            serde_json::json!({
                "key": f.key, "start": num(f.start), "value": num(f.value), "stderr": num(f.stderr),
                "stderr_statistical": num(f.stderr_statistical),
                "stderr_profile": [num(f.stderr_profile[0]), num(f.stderr_profile[1])], "bounds": [num(f.bounds[0]), num(f.bounds[1])],
                "prior": p.prior.map(|pr| serde_json::json!({"mean": pr.mean, "sd": pr.sd})),
                "at_bound": f.at_bound, "profile_likelihood": profile,
            })
        })
        .collect();
    let reference = &problem.reference;
    let json = serde_json::json!({
        "calibration": problem.cal.file.display().to_string(),
        "base": problem.cal.base.display().to_string(),
        "name": problem.cal.meta.name,
        "reference": {
            "runs": problem.cal.reference.runs.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
            "data": problem.cal.reference.data,
            "seeds": reference.seeds,
            "smooth_m": num(reference.h_g),
            "align": reference.align,
            "terms": reference.profiles.iter().map(|t| serde_json::json!({
                "term": t.name, "rows": t.z.len(), "independent": num(t.independent), "scatter": num(t.scatter),
                "z_min": num(t.z.first().copied().unwrap_or(f64::NAN)), "z_max": num(t.z.last().copied().unwrap_or(f64::NAN)),
            })).chain(reference.rate.iter().map(|q| serde_json::json!({"term": "qs_star", "mean": num(q.mean), "scatter": num(q.scatter)}))).collect::<Vec<_>>(),
        },
        "parameters": fitted,
        "correlation": matrix(&r.correlation),
        "covariance": matrix(&r.covariance),
        "misfit": {
            "start": terms(&r.start_terms),
            "optimum": terms(&r.optimum_terms),
            "chi2_start": num(r.chi2_start),
            "chi2": num(r.chi2),
            "dof": num(r.dof),
            "error_scale": num((r.chi2 / r.dof).max(1.0).sqrt()),
        },
        "optimiser": {
            "method": "Levenberg-Marquardt (MINPACK lmder, crate levenberg-marquardt), bounds by the MINUIT sine transformation, central-difference Jacobian",
            "reason": r.reason,
            "converged": r.converged,
            "runs_to_optimum": r.evaluations_minimise,
            "runs": r.evaluations,
            "cpu_time_s": num(r.cpu_time_s),
            "wall_time_s": num(r.wall_time_s),
        },
        "warnings": r.warnings,
    });
    write(out.join(JSON), &serde_json::to_string_pretty(&json)?)
}
