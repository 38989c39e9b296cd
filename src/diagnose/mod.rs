//! `saltus diagnose`: granular closures evaluated on the averaged fields of a run and
//! held against them (the method of Chassagne et al. 2023 section 3 and Fry et al. 2024
//! section IV). The definitions and equations are in `docs/diagnostics.md`.
//!
//! Every number comes from a closure ([`local`], [`kinetic`]) or from the run's
//! profiles; this module only selects the cells and the closures and writes the results.

pub mod closures;
pub mod comparison;
pub mod fields;
pub mod fit;
pub mod kinetic;
pub mod local;
pub mod viscosity;

use std::path::{Path, PathBuf};

use anyhow::bail;

pub use comparison::Comparison;
pub use fields::RunFields;
pub use fit::{ClosureFit, QuantityFit, Window};
pub use kinetic::{BandFit, G0Fit, G0_FIT_BANDS};

/// Default lowest volume fraction of a usable cell: below it the averages of a DEM
/// slice rest on a few grains crossing it and the continuum closures are not meant to
/// hold (Chassagne et al. 2023 figure 6 shows the kinetic theory failing below phi ~
/// 0.2 without the saltation correction).
pub const PHI_MIN: f64 = 0.1;

/// Options of a diagnosis.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// cells with phi <= this are not used
    pub phi_min: f64,
    /// fit the closures' parameters (`--fit`)
    pub fit: bool,
    /// the cells the fits use besides those of their comparisons
    pub window: Window,
}

impl Default for Options {
    fn default() -> Self {
        Options { phi_min: PHI_MIN, fit: false, window: Window::default() }
    }
}

/// File of the fitted closure tables, in the diagnose folder.
pub const FITTED: &str = "fitted.toml";

/// What one closure's comparisons found.
#[derive(Clone, Debug)]
pub struct ClosureDiagnosis {
    /// the closure's label
    pub label: String,
    /// its model name
    pub model: String,
    /// its comparisons
    pub comparisons: Vec<Comparison>,
    /// kinetic closures: the coefficient a of eq 3.2 fitted to the extracted g0
    pub g0_fit: Option<G0Fit>,
    /// with `--fit`: its parameters fitted to the run
    pub fit: Option<ClosureFit>,
    /// the closure's table as a scene writes it (the start of its fit)
    pub table: toml::Table,
}

/// What [`Diagnosis::write`] wrote.
#[derive(Clone, Debug, Default)]
pub struct Written {
    /// the files written
    pub files: Vec<PathBuf>,
    /// the comparisons that could not be written, each naming its closure, quantity and
    /// why
    pub warnings: Vec<String>,
}

/// Every closure's comparisons on one run.
#[derive(Clone, Debug)]
pub struct Diagnosis {
    /// the run's output folder
    pub dir: PathBuf,
    /// further runs whose cells were pooled with this one's ([`diagnose_pooled`])
    pub pooled: Vec<PathBuf>,
    /// the run's number of cells
    pub cells: usize,
    /// the lowest phi of a usable cell
    pub phi_min: f64,
    /// one entry per closure
    pub closures: Vec<ClosureDiagnosis>,
    /// the window of the fits
    pub window: Window,
    /// the fluid-phase viscosity exponent of the run, or why the run does not measure it
    pub viscosity_fit: Result<viscosity::ViscosityFit, String>,
    /// the run's grains (what the closures inherit)
    pub particles: saltus_core::scene::Particles,
}

/// Evaluate the closures of `closure_args` (or the scene's, or the library defaults) on
/// the run whose output folder is `dir`.
pub fn diagnose(dir: &Path, closure_args: &[String], opts: Options) -> anyhow::Result<Diagnosis> {
    diagnose_pooled(&[dir.to_path_buf()], closure_args, opts)
}

/// [`diagnose`] over several runs of one scene (seeds): each run is diagnosed on its own,
/// then the cells of each comparison are pooled, in the order of `dirs`, and the fits
/// (with `opts.fit`) are made on the pooled cells, so that their residuals hold the
/// run-to-run scatter. The runs must have the same grains and closures.
pub fn diagnose_pooled(dirs: &[PathBuf], closure_args: &[String], opts: Options) -> anyhow::Result<Diagnosis> {
    let Some((first, rest)) = dirs.split_first() else { bail!("no run folder given") };
    let unfitted = Options { fit: false, ..opts };
    let mut fields = RunFields::read(first)?;
    let mut d = diagnose_fields(&mut fields, closure_args, unfitted)?;
    d.dir = first.clone();
    for dir in rest {
        let mut other = RunFields::read(dir)?;
        if other.scene.particles != d.particles {
            bail!(
                "{}: its [particles] differ from those of {}; pool runs of one scene only",
                dir.display(),
                first.display()
            );
        }
        let o = diagnose_fields(&mut other, closure_args, unfitted)?;
        for cd in &mut d.closures {
            let Some(oc) = o.closures.iter().find(|c| c.label == cd.label && c.model == cd.model) else {
                bail!("{}: has no closure `{}` to pool with {}", dir.display(), cd.label, first.display());
            };
            for c in &mut cd.comparisons {
                if let Some(x) = oc.comparisons.iter().find(|x| x.quantity == c.quantity) {
                    c.append(x);
                }
            }
        }
        d.pooled.push(dir.clone());
    }
    if opts.fit {
        d.fit()?;
    }
    Ok(d)
}

/// [`diagnose`] of fields already read (or held in memory: [`RunFields::new`]).
pub fn diagnose_fields(fields: &mut RunFields, closure_args: &[String], opts: Options) -> anyhow::Result<Diagnosis> {
    if !(opts.phi_min.is_finite() && (0.0..1.0).contains(&opts.phi_min)) {
        bail!("--phi-min {}: allowed a volume fraction in [0, 1)", opts.phi_min);
    }
    let w = opts.window;
    for (name, z) in [("--z-min", w.z_min), ("--z-max", w.z_max)] {
        if let Some(z) = z.filter(|z| !z.is_finite()) {
            bail!("{name} {z}: allowed a height in metres (a finite number)");
        }
    }
    if let (Some(lo), Some(hi)) = (w.z_min, w.z_max) {
        if lo >= hi {
            bail!("--z-min {lo} --z-max {hi}: the window is empty; give z-min < z-max");
        }
    }
    let named = closures::select(closure_args, &mut fields.scene)?;
    let mut out = Vec::new();
    for n in named {
        let model = n.closure.name().to_string();
        let (comparisons, g0_fit) = if let Some(local) = n.closure.as_local() {
            (local::compare(&n.label, local, fields, opts.phi_min)?, None)
        } else if let Some(kt) = n.closure.as_kinetic() {
            let (c, fit) = kinetic::compare(&n.label, kt, fields, opts.phi_min)?;
            (c, Some(fit))
        } else {
            bail!("closure `{}` ({model}) is neither a local rheology nor a kinetic theory", n.label);
        };
        let table = fit::table_of(n.closure.as_ref())?;
        out.push(ClosureDiagnosis { label: n.label, model, comparisons, g0_fit, fit: None, table });
    }
    let dir = fields.profiles_path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    let mut d = Diagnosis {
        dir,
        pooled: Vec::new(),
        cells: fields.rows(),
        phi_min: opts.phi_min,
        closures: out,
        window: opts.window,
        viscosity_fit: viscosity::fit(fields),
        particles: fields.scene.particles.clone(),
    };
    if opts.fit {
        d.fit()?;
    }
    Ok(d)
}

impl Diagnosis {
    /// Fit every closure's parameters on the comparisons' cells in the window.
    pub fn fit(&mut self) -> anyhow::Result<()> {
        for cd in &mut self.closures {
            let closure = saltus_core::scene::granular_from_value(
                toml::Value::Table(cd.table.clone()),
                &self.particles,
                Path::new("diagnose"),
                &cd.label,
            )?;
            cd.fit =
                Some(fit::fit_closure(&cd.label, closure.as_ref(), &cd.comparisons, &self.particles, self.window)?);
        }
        Ok(())
    }

    /// Every comparison, closure by closure.
    pub fn comparisons(&self) -> impl Iterator<Item = &Comparison> {
        self.closures.iter().flat_map(|c| &c.comparisons)
    }

    /// The comparison of `quantity` of closure `label`.
    pub fn find(&self, label: &str, quantity: &str) -> Option<&Comparison> {
        self.comparisons().find(|c| c.closure == label && c.quantity == quantity)
    }

    /// Write `summary.csv` and every comparison's CSV and PNG into `out`; returns the
    /// files written. A comparison whose files cannot be written is told in the warnings,
    /// naming its closure, quantity and file, and the others are written all the same.
    pub fn write(&self, out: &Path) -> anyhow::Result<Written> {
        std::fs::create_dir_all(out).map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", out.display()))?;
        let mut written = Vec::new();
        let summary = out.join("summary.csv");
        let mut text = String::from("closure,model,quantity,cells,rms,relative_rms,relative_bias\n");
        for cd in &self.closures {
            for c in &cd.comparisons {
                let num = |x: f64| if x.is_finite() { format!("{x:e}") } else { String::new() };
                text.push_str(&format!(
                    "{},{},{},{},{},{},{}\n",
                    cd.label,
                    cd.model,
                    c.quantity,
                    c.cells(),
                    num(c.rms()),
                    num(c.relative_rms()),
                    num(c.relative_bias())
                ));
            }
        }
        std::fs::write(&summary, text).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", summary.display()))?;
        written.push(summary);
        let fits: Vec<_> = self.closures.iter().filter_map(|cd| cd.g0_fit.map(|f| (cd, f))).collect();
        if !fits.is_empty() {
            let path = out.join("g0_fit.csv");
            let num = |x: f64| if x.is_finite() { format!("{x:e}") } else { String::new() };
            let mut text = String::from("closure,model,phi_lo,phi_hi,cells,a,a_stderr,a_eq33,mu_p\n");
            for (cd, f) in fits {
                let all = kinetic::BandFit {
                    phi_lo: self.phi_min,
                    phi_hi: 1.0,
                    a: f.a,
                    a_stderr: f.a_stderr,
                    cells: f.cells,
                };
                for b in std::iter::once(all).chain(f.bands) {
                    text.push_str(&format!(
                        "{},{},{},{},{},{},{},{},{}\n",
                        cd.label,
                        cd.model,
                        b.phi_lo,
                        b.phi_hi,
                        b.cells,
                        num(b.a),
                        num(b.a_stderr),
                        num(f.a_eq33),
                        f.mu_p
                    ));
                }
            }
            std::fs::write(&path, text).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))?;
            written.push(path);
        }
        let mut first = true;
        for cd in &self.closures {
            let Some(f) = &cd.fit else { continue };
            let runs: Vec<&Path> =
                std::iter::once(self.dir.as_path()).chain(self.pooled.iter().map(PathBuf::as_path)).collect();
            let Some(text) = fit::fitted_toml(f, &runs, self.phi_min, self.window, &self.viscosity_fit) else {
                continue;
            };
            let mut names = vec![format!("fitted-{}.toml", crate::compare::slug(&cd.label))];
            if first {
                names.insert(0, FITTED.to_string());
                first = false;
            }
            for name in names {
                let path = out.join(name);
                std::fs::write(&path, &text).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))?;
                written.push(path);
            }
        }
        let mut warnings = Vec::new();
        for c in self.comparisons().filter(|c| c.cells() > 0) {
            match c.write(out) {
                Ok(files) => written.extend(files),
                Err(e) => warnings.push(format!(
                    "{}: {} of `{}` ({} cells) not written: {e:#}",
                    out.display(),
                    c.quantity,
                    c.closure,
                    c.cells()
                )),
            }
        }
        Ok(Written { files: written, warnings })
    }

    /// The short table printed by the command.
    pub fn text(&self) -> String {
        use comparison::figure;
        let mut s = format!(
            "{}: {} cells, used where phi > {}, p_p > 0 and the fields are defined\n",
            self.dir.display(),
            self.cells,
            self.phi_min
        );
        for p in &self.pooled {
            s.push_str(&format!("pooled with the cells of {}\n", p.display()));
        }
        s.push_str(&format!(
            "{:<24} {:<32} {:>6} {:>12} {:>12} {:>12}\n",
            "closure", "quantity", "cells", "rms", "rel. rms", "rel. bias"
        ));
        for cd in &self.closures {
            for c in &cd.comparisons {
                s.push_str(&format!(
                    "{:<24} {:<32} {:>6} {:>12} {:>12} {:>12}\n",
                    cd.label,
                    c.quantity,
                    c.cells(),
                    figure(c.rms()),
                    figure(c.relative_rms()),
                    figure(c.relative_bias())
                ));
            }
            if let Some(fit) = cd.g0_fit {
                s.push_str(&format!(
                    "{:<24} a of eq 3.2 fitted to the extracted g0: {} +- {} over {} cells; eq 3.3 at mu_p = {}: {}\n",
                    cd.label,
                    figure(fit.a),
                    figure(fit.a_stderr),
                    fit.cells,
                    fit.mu_p,
                    figure(fit.a_eq33)
                ));
                let bands: Vec<String> = fit
                    .bands
                    .iter()
                    .map(|b| {
                        format!(
                            "[{}, {}): {} +- {} ({} cells)",
                            b.phi_lo,
                            b.phi_hi,
                            figure(b.a),
                            figure(b.a_stderr),
                            b.cells
                        )
                    })
                    .collect();
                s.push_str(&format!("{:<24} the same fit by band of phi: {}\n", cd.label, bands.join("; ")));
            }
        }
        let fits: Vec<&ClosureFit> = self.closures.iter().filter_map(|c| c.fit.as_ref()).collect();
        if !fits.is_empty() {
            s.push_str(&self.fit_text(&fits));
        }
        s
    }

    /// The fits as JSON (the Python `saltus.diagnose`): per closure, per quantity, each
    /// fit tried with its parameters and either its values, standard errors, cells and
    /// residual RMS, or the reason the cells cannot support it; undefined numbers are null.
    pub fn fits_json(&self) -> serde_json::Value {
        use serde_json::json;
        let num = |x: f64| if x.is_finite() { json!(x) } else { serde_json::Value::Null };
        let nums = |v: &[f64]| v.iter().map(|x| num(*x)).collect::<Vec<_>>();
        let closures: Vec<_> = self
            .closures
            .iter()
            .filter_map(|cd| cd.fit.as_ref())
            .map(|f| {
                let quantities: Vec<_> = f
                    .quantities
                    .iter()
                    .map(|q| {
                        let attempts: Vec<_> = q
                            .attempts
                            .iter()
                            .map(|a| match &a.result {
                                Ok(s) => json!({
                                    "params": a.params, "values": nums(&s.params), "stderr": nums(&s.stderr),
                                    "stderr_independent": nums(&s.stderr_independent), "cells": s.points,
                                    "residual_rms": num(s.rms), "residual_lag1": num(s.r1),
                                }),
                                Err(reason) => json!({ "params": a.params, "reason": reason }),
                            })
                            .collect();
                        json!({
                            "quantity": q.quantity, "control": q.control, "held": q.held(),
                            "kept": q.kept().is_some(), "x_range": nums(&[q.x_range.0, q.x_range.1]),
                            "z_range": nums(&[q.z_range.0, q.z_range.1]), "attempts": attempts,
                        })
                    })
                    .collect();
                let unsupported: Vec<_> =
                    f.unsupported.iter().map(|(q, r)| json!({ "quantity": q, "reason": r })).collect();
                json!({
                    "closure": f.label, "model": f.model, "quantities": quantities, "unsupported": unsupported,
                    "table": f.table.as_ref().map(|t| serde_json::to_value(t).unwrap_or(serde_json::Value::Null)),
                })
            })
            .collect();
        json!({
            "phi_min": self.phi_min, "z_min": self.window.z_min, "z_max": self.window.z_max,
            "closures": closures, "viscosity": match &self.viscosity_fit {
                Ok(v) => json!({
                    "beta0": v.solution.params[0], "stderr": v.solution.stderr[0],
                    "stderr_independent": v.solution.stderr_independent[0], "cells": v.solution.points,
                }),
                Err(reason) => json!({ "unsupported": reason }),
            },
        })
    }

    /// The fits' part of the printed table.
    fn fit_text(&self, fits: &[&ClosureFit]) -> String {
        use comparison::figure;
        let w = self.window;
        let bound = |z: Option<f64>| z.map_or_else(|| "-".to_string(), |z| format!("{z}"));
        let mut s = format!(
            "fits (cells with phi > {}, z in [{}, {}] m; +- the standard error counting the lag-1 correlation of the \
             residuals, [cells independent]):\n",
            self.phi_min,
            bound(w.z_min),
            bound(w.z_max)
        );
        for f in fits {
            for q in &f.quantities {
                for a in &q.attempts {
                    match &a.result {
                        Ok(sol) => {
                            let values: Vec<String> = a
                                .params
                                .iter()
                                .enumerate()
                                .map(|(i, p)| {
                                    format!(
                                        "{p} = {} +- {} [{}]",
                                        figure(sol.params[i]),
                                        figure(sol.stderr[i]),
                                        figure(sol.stderr_independent[i])
                                    )
                                })
                                .collect();
                            let held = q.held();
                            let held =
                                if held.is_empty() { String::new() } else { format!("; held: {}", held.join(", ")) };
                            s.push_str(&format!(
                                "{:<24} {}: {} over {} cells, {} in [{}, {}], residual RMS {}{held}\n",
                                f.label,
                                q.quantity,
                                values.join(", "),
                                sol.points,
                                q.control,
                                figure(q.x_range.0),
                                figure(q.x_range.1),
                                figure(sol.rms)
                            ));
                        }
                        Err(reason) => s.push_str(&format!(
                            "{:<24} {} ({}): not fitted: {reason}\n",
                            f.label,
                            q.quantity,
                            a.params.join(", ")
                        )),
                    }
                }
            }
            for (what, reason) in &f.unsupported {
                s.push_str(&format!("{:<24} {what}: not fitted: {reason}\n", f.label));
            }
        }
        match &self.viscosity_fit {
            Ok(v) => {
                let sol = &v.solution;
                s.push_str(&format!(
                    "{}: beta0 = {} +- {} [{}] over {} cells with {} < phi <= {}, residual RMS {} (fry2024 with a = 0)\n",
                    viscosity::QUANTITY,
                    figure(sol.params[0]),
                    figure(sol.stderr[0]),
                    figure(sol.stderr_independent[0]),
                    sol.points,
                    viscosity::PHI_RANGE.0,
                    viscosity::PHI_RANGE.1,
                    figure(sol.rms)
                ));
            }
            Err(reason) => s.push_str(&format!("{}: not fitted: {reason}\n", viscosity::QUANTITY)),
        }
        s
    }
}
