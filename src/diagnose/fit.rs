//! `diagnose --fit`: the parameters of the granular closures compared, fitted to the
//! run's averaged fields over a window of cells, and written as closure tables
//! (`fitted.toml`) that `saltus run --closures` takes.
//!
//! Each quantity is fitted by least squares ([`least_squares`]) of
//! the closure's own prediction against the measured values of the cells its comparison
//! uses: mu(X) for (mu_s, mu_2, I0) of `mu_i` and (mu_1, mu_2, sqrt(K0)) of `mu_k`,
//! phi(X) for (phi_c, b), and the relative regression of eq 3.2 for a of
//! `frictional_collisional` (Chassagne et al. 2023). When the cells cannot determine every
//! parameter (one inclination gives one mu at every height), the full fit is reported
//! with its reason and the parameters are released one fewer at a time, the others held
//! at the closure's values; the held ones are stated.

use std::path::Path;

use anyhow::Context;
use saltus_core::grain::carnahan_starling;
use saltus_core::scene::{granular_from_value, to_toml_table, Particles};
use saltus_core::GranularStress;

use super::comparison::Comparison;
use crate::least_squares::{self, Solution};

/// The cells a fit uses besides those of its comparison.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Window {
    /// lowest cell centre (m)
    pub z_min: Option<f64>,
    /// highest cell centre (m)
    pub z_max: Option<f64>,
}

impl Window {
    fn contains(&self, z: f64) -> bool {
        self.z_min.is_none_or(|lo| z >= lo) && self.z_max.is_none_or(|hi| z <= hi)
    }
}

/// One fit of a set of parameters.
#[derive(Clone, Debug)]
pub struct Attempt {
    /// parameters fitted (the others of the quantity held at the closure's values)
    pub params: Vec<String>,
    /// the fit, or why the cells cannot support it
    pub result: Result<Solution, String>,
}

/// The fit of one quantity of one closure.
#[derive(Clone, Debug)]
pub struct QuantityFit {
    /// the comparison fitted, e.g. `mu(I)`, `g0 closure`
    pub quantity: String,
    /// its control number (`I`, `K`, `phi`)
    pub control: String,
    /// every parameter of the quantity, as the closure's table names it
    pub all: Vec<String>,
    /// range of the control number over the cells used
    pub x_range: (f64, f64),
    /// range of z over the cells used
    pub z_range: (f64, f64),
    /// the fits tried, the full one first; the last is the one kept when it succeeded
    pub attempts: Vec<Attempt>,
}

impl QuantityFit {
    /// The fit kept: the last attempt, when it succeeded.
    pub fn kept(&self) -> Option<(&Attempt, &Solution)> {
        self.attempts.last().and_then(|a| a.result.as_ref().ok().map(|s| (a, s)))
    }

    /// Parameters held at the closure's values in the fit kept.
    pub fn held(&self) -> Vec<String> {
        let fitted = self.kept().map(|(a, _)| a.params.clone()).unwrap_or_default();
        self.all.iter().filter(|p| !fitted.contains(p)).cloned().collect()
    }
}

/// What the fit of one closure found.
#[derive(Clone, Debug)]
pub struct ClosureFit {
    /// the closure's label
    pub label: String,
    /// its model name
    pub model: String,
    /// one per quantity fitted
    pub quantities: Vec<QuantityFit>,
    /// quantities of the closure no run of this kind can fit, with the reason
    pub unsupported: Vec<(String, String)>,
    /// the closure table with the fitted values, when at least one quantity was fitted
    pub table: Option<toml::Table>,
}

/// The parameters of each quantity of the models fitted.
fn specs(model: &str) -> Option<&'static [(&'static str, &'static [&'static str])]> {
    match model {
        "mu_i" => Some(&[("mu(I)", &["mu_s", "mu_2", "i0"]), ("phi(I)", &["phi_c", "b"])]),
        "mu_k" => Some(&[("mu(K)", &["mu_1", "mu_2", "sqrt_k0"]), ("phi(K)", &["phi_c", "b"])]),
        "frictional_collisional" => Some(&[("g0 closure", &["a"])]),
        _ => None,
    }
}

/// The closure's own table (with `type`), as a scene writes it.
pub fn table_of(closure: &dyn GranularStress) -> anyhow::Result<toml::Table> {
    let text = to_toml_table(closure).map_err(|e| anyhow::anyhow!("cannot write the closure as TOML: {e}"))?;
    text.parse::<toml::Table>().context("the closure's TOML does not read back")
}

/// Fit the closure `closure` (label `label`) on its `comparisons` of this run.
pub fn fit_closure(
    label: &str,
    closure: &dyn GranularStress,
    comparisons: &[Comparison],
    particles: &Particles,
    window: Window,
) -> anyhow::Result<ClosureFit> {
    let model = closure.name().to_string();
    let mut out = ClosureFit {
        label: label.into(),
        model: model.clone(),
        quantities: Vec::new(),
        unsupported: Vec::new(),
        table: None,
    };
    let Some(specs) = specs(&model) else {
        out.unsupported.push((
            "every parameter".into(),
            format!("no fit is defined for model `{model}` (fitted: mu_i, mu_k, frictional_collisional)"),
        ));
        return Ok(out);
    };
    let base = table_of(closure)?;
    let mut fitted = base.clone();
    for &(quantity, params) in specs {
        let Some(c) = comparisons.iter().find(|c| c.quantity == quantity) else { continue };
        let cells: Vec<usize> = (0..c.cells()).filter(|&k| window.contains(c.z[k])).collect();
        let range = |v: &[f64]| {
            cells.iter().map(|&k| v[k]).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
        };
        let mut q = QuantityFit {
            quantity: quantity.into(),
            control: c.control.into(),
            all: params.iter().map(|p| p.to_string()).collect(),
            x_range: range(&c.x),
            z_range: range(&c.z),
            attempts: Vec::new(),
        };
        if model == "frictional_collisional" {
            let Some(kt) = closure.as_kinetic() else { continue };
            // eq 3.2 as the relative regression of `kinetic`: (g0 - g0_CS)/g0 = a x / g0
            let (x, y): (Vec<f64>, Vec<f64>) = cells
                .iter()
                .map(|&k| {
                    let (phi, g0) = (c.x[k], c.measured[k]);
                    (kt.radial_distribution_regressor(phi) / g0, (g0 - carnahan_starling(phi)) / g0)
                })
                .unzip();
            let a0 = base.get("g0").and_then(|g| g.get("a")).and_then(|a| a.as_float()).unwrap_or(1.0);
            let result = least_squares::fit(&["a"], &[a0], x.len(), |p| {
                (p[0] >= 0.0).then(|| x.iter().zip(&y).map(|(x, y)| p[0] * x - y).collect())
            });
            if let Ok(s) = &result {
                let mut g0 = toml::Table::new();
                g0.insert("type".into(), "chialvo_sundaresan".into());
                g0.insert("a".into(), s.params[0].into());
                fitted.insert("g0".into(), toml::Value::Table(g0));
            }
            q.attempts.push(Attempt { params: vec!["a".into()], result });
            out.quantities.push(q);
            out.unsupported.push((
                "a(mu_p) of eq 3.3 (a0, a_max, delta)".into(),
                format!(
                    "one run has one interparticle friction (mu_p = {}); eq 3.3 needs runs at several; a of eq 3.2 at this mu_p is fitted instead",
                    particles.friction
                ),
            ));
            continue;
        }
        let is_mu = quantity.starts_with("mu(");
        for released in (1..=params.len()).rev() {
            let names = &params[..released];
            let p0: Vec<f64> =
                names.iter().map(|n| fitted.get(*n).and_then(|v| v.as_float()).unwrap_or(f64::NAN)).collect();
            let residuals = |p: &[f64]| -> Option<Vec<f64>> {
                let mut t = fitted.clone();
                for (n, v) in names.iter().zip(p) {
                    t.insert(n.to_string(), (*v).into());
                }
                let m = granular_from_value(toml::Value::Table(t), particles, Path::new("fit"), "fit").ok()?;
                let local = m.as_local()?;
                Some(
                    cells
                        .iter()
                        .map(|&k| {
                            let pred = if is_mu { local.friction(c.x[k]) } else { local.packing(c.x[k]) };
                            pred - c.measured[k]
                        })
                        .collect(),
                )
            };
            let result = if p0.iter().all(|v| v.is_finite()) {
                least_squares::fit(names, &p0, cells.len(), residuals).and_then(|s| determined(names, s)).and_then(
                    |s| {
                        if names.len() < 2 {
                            return Ok(s);
                        }
                        // the curve's change over the window must be resolved before more
                        // than its level is fitted
                        let (lo, hi) = q.x_range;
                        let at = |p: &[f64], x: f64| -> Option<f64> {
                            let mut t = fitted.clone();
                            for (n, v) in names.iter().zip(p) {
                                t.insert(n.to_string(), (*v).into());
                            }
                            let m =
                                granular_from_value(toml::Value::Table(t), particles, Path::new("fit"), "fit").ok()?;
                            let l = m.as_local()?;
                            Some(if is_mu { l.friction(x) } else { l.packing(x) })
                        };
                        resolved_change(&s, lo, hi, at).map(|_| s)
                    },
                )
            } else {
                Err(format!("the closure's table has no number for one of {names:?}"))
            };
            let ok = result.is_ok();
            if let Ok(s) = &result {
                for (n, v) in names.iter().zip(&s.params) {
                    fitted.insert(n.to_string(), (*v).into());
                }
            }
            q.attempts.push(Attempt { params: names.iter().map(|s| s.to_string()).collect(), result });
            if ok || cells.len() < least_squares::min_points(1) {
                break;
            }
        }
        out.quantities.push(q);
    }
    if out.quantities.iter().any(|q| q.kept().is_some()) {
        // the table must build as a scene builds it
        granular_from_value(
            toml::Value::Table(fitted.clone()),
            particles,
            Path::new("fitted.toml"),
            "closures.granular",
        )
        .map_err(|e| anyhow::anyhow!("the fitted closure of `{label}` does not build: {e}"))?;
        out.table = Some(fitted);
    }
    Ok(out)
}

/// A fit whose every standard error is finite and below the value's magnitude; else the
/// parameter the cells do not determine.
fn determined(names: &[&str], s: Solution) -> Result<Solution, String> {
    for (i, n) in names.iter().enumerate() {
        let (v, e) = (s.params[i], s.stderr[i]);
        if !(v.is_finite() && e.is_finite()) {
            return Err(format!("`{n}` has no finite value or standard error"));
        }
        if e >= v.abs() {
            return Err(format!("`{n}` is not determined by these cells: {v:.4e} +- {e:.4e}"));
        }
    }
    Ok(s)
}

/// The change f(hi) - f(lo) of the fitted curve over the window and its standard error
/// (the delta method with the fit's covariance): an error unless it exceeds twice its
/// standard error, i.e. unless the cells resolve how the quantity varies with the
/// control number, which every parameter beyond the level describes.
fn resolved_change(s: &Solution, lo: f64, hi: f64, at: impl Fn(&[f64], f64) -> Option<f64>) -> Result<(), String> {
    let m = s.params.len();
    let change = |p: &[f64]| -> Option<f64> { Some(at(p, hi)? - at(p, lo)?) };
    let d = change(&s.params).ok_or("the fitted closure cannot be evaluated over the window")?;
    let mut g = vec![0.0; m];
    for k in 0..m {
        let h = 1e-6 * s.params[k].abs().max(1e-3);
        let mut q = s.params.clone();
        q[k] += h;
        let dq = change(&q).or_else(|| {
            q[k] -= 2.0 * h;
            change(&q).map(|v| 2.0 * d - v)
        });
        g[k] = (dq.ok_or("the fitted closure cannot be evaluated near the fit")? - d) / h;
    }
    let var: f64 =
        (0..m).flat_map(|i| (0..m).map(move |k| (i, k))).map(|(i, k)| g[i] * s.covariance[i * m + k] * g[k]).sum();
    let se = var.max(0.0).sqrt();
    if d.abs() > 2.0 * se {
        Ok(())
    } else {
        Err(format!(
            "the cells do not resolve the change over the window ({lo:.4e} to {hi:.4e}): {d:.4e} +- {se:.4e}; only the level is determined"
        ))
    }
}

/// The `fitted.toml` text of `fit`: comments, `[closures.granular]`, and a `[fit]` table
/// of metadata (the run, the window, each quantity's fitted and held parameters, values,
/// standard errors, residual RMS, and the fits the cells could not support with their
/// reasons). None when no quantity was fitted.
pub fn fitted_toml(
    fit: &ClosureFit,
    runs: &[&Path],
    phi_min: f64,
    window: Window,
    viscosity: &Result<super::viscosity::ViscosityFit, String>,
) -> Option<String> {
    let table = fit.table.clone()?;
    let mut meta = toml::Table::new();
    meta.insert("runs".into(), toml::Value::Array(runs.iter().map(|r| r.display().to_string().into()).collect()));
    meta.insert("closure".into(), fit.label.clone().into());
    meta.insert("phi_min".into(), phi_min.into());
    if let Some(z) = window.z_min {
        meta.insert("z_min".into(), z.into());
    }
    if let Some(z) = window.z_max {
        meta.insert("z_max".into(), z.into());
    }
    let mut quantities = Vec::new();
    let mut rejected = Vec::new();
    for q in &fit.quantities {
        for a in &q.attempts {
            if let Err(reason) = &a.result {
                let mut r = toml::Table::new();
                r.insert("quantity".into(), q.quantity.clone().into());
                r.insert("params".into(), strings(&a.params));
                r.insert("reason".into(), reason.clone().into());
                rejected.push(toml::Value::Table(r));
            }
        }
        let Some((a, s)) = q.kept() else { continue };
        let mut t = toml::Table::new();
        t.insert("quantity".into(), q.quantity.clone().into());
        t.insert("control".into(), q.control.clone().into());
        t.insert("cells".into(), (s.points as i64).into());
        t.insert("x_min".into(), q.x_range.0.into());
        t.insert("x_max".into(), q.x_range.1.into());
        t.insert("z_min".into(), q.z_range.0.into());
        t.insert("z_max".into(), q.z_range.1.into());
        t.insert("params".into(), strings(&a.params));
        t.insert("values".into(), numbers(&s.params));
        t.insert("stderr".into(), numbers(&s.stderr));
        t.insert("stderr_independent".into(), numbers(&s.stderr_independent));
        t.insert("residual_rms".into(), s.rms.into());
        t.insert("residual_lag1".into(), s.r1.into());
        t.insert("held".into(), strings(&q.held()));
        quantities.push(toml::Value::Table(t));
    }
    for (what, reason) in &fit.unsupported {
        let mut r = toml::Table::new();
        r.insert("quantity".into(), what.clone().into());
        r.insert("reason".into(), reason.clone().into());
        rejected.push(toml::Value::Table(r));
    }
    let mut closures = toml::Table::new();
    match viscosity {
        Ok(v) => {
            let s = &v.solution;
            let mut t = toml::Table::new();
            t.insert("quantity".into(), super::viscosity::QUANTITY.into());
            t.insert("control".into(), "phi".into());
            t.insert("cells".into(), (s.points as i64).into());
            t.insert("x_min".into(), super::viscosity::PHI_RANGE.0.into());
            t.insert("x_max".into(), super::viscosity::PHI_RANGE.1.into());
            t.insert("z_min".into(), v.z_range.0.into());
            t.insert("z_max".into(), v.z_range.1.into());
            t.insert("params".into(), strings(&["beta0".to_string()]));
            t.insert("values".into(), numbers(&s.params));
            t.insert("stderr".into(), numbers(&s.stderr));
            t.insert("stderr_independent".into(), numbers(&s.stderr_independent));
            t.insert("residual_rms".into(), s.rms.into());
            t.insert("residual_lag1".into(), s.r1.into());
            t.insert("held".into(), strings(&["a = 0".to_string()]));
            quantities.push(toml::Value::Table(t));
            closures.insert("viscosity".into(), toml::Value::Table(super::viscosity::closure_table(v)));
        }
        Err(reason) => {
            let mut r = toml::Table::new();
            r.insert("quantity".into(), super::viscosity::QUANTITY.into());
            r.insert("reason".into(), reason.clone().into());
            rejected.push(toml::Value::Table(r));
        }
    }
    meta.insert("quantity".into(), toml::Value::Array(quantities));
    meta.insert("rejected".into(), toml::Value::Array(rejected));
    closures.insert("granular".into(), toml::Value::Table(table));
    let mut doc = toml::Table::new();
    doc.insert("closures".into(), toml::Value::Table(closures));
    doc.insert("fit".into(), toml::Value::Table(meta));
    let body = toml::to_string(&doc).ok()?;
    Some(format!(
        "# Closure tables fitted by `saltus diagnose --fit` on the averaged fields of {}.\n\
         # Load with `saltus run SCENE --closures THIS_FILE`: [closures.granular] (and [closures.viscosity]\n\
         # when the run measures it) replace the scene's;\n\
         # [fit] is metadata (window, fitted and held parameters, standard errors, residuals, the\n\
         # fits the cells could not support), ignored by the loader. `stderr` counts the lag-1\n\
         # correlation of the residuals between neighbouring cells; `stderr_independent` takes the\n\
         # cells as independent. Pooled runs (several folders) put the run-to-run scatter in the residuals.\n\n{body}",
        runs.iter().map(|r| r.display().to_string()).collect::<Vec<_>>().join(", ")
    ))
}

fn strings(v: &[String]) -> toml::Value {
    toml::Value::Array(v.iter().map(|s| s.clone().into()).collect())
}

fn numbers(v: &[f64]) -> toml::Value {
    toml::Value::Array(v.iter().map(|x| (*x).into()).collect())
}
