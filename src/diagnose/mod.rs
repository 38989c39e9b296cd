//! `saltus diagnose`: granular closures evaluated on the averaged fields of a run and
//! held against them (the method of Chassagne et al. 2023 section 3 and Fry et al. 2024
//! section IV). The definitions and equations are in `docs/diagnostics.md`.
//!
//! Every number comes from a closure ([`local`], [`kinetic`]) or from the run's
//! profiles; this module only selects the cells and the closures and writes the results.

pub mod closures;
pub mod comparison;
pub mod fields;
pub mod kinetic;
pub mod local;

use std::path::{Path, PathBuf};

use anyhow::bail;

pub use comparison::Comparison;
pub use fields::RunFields;
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
}

impl Default for Options {
    fn default() -> Self {
        Options { phi_min: PHI_MIN }
    }
}

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
    /// the run's number of cells
    pub cells: usize,
    /// the lowest phi of a usable cell
    pub phi_min: f64,
    /// one entry per closure
    pub closures: Vec<ClosureDiagnosis>,
}

/// Evaluate the closures of `closure_args` (or the scene's, or the library defaults) on
/// the run whose output folder is `dir`.
pub fn diagnose(dir: &Path, closure_args: &[String], opts: Options) -> anyhow::Result<Diagnosis> {
    let mut fields = RunFields::read(dir)?;
    let mut d = diagnose_fields(&mut fields, closure_args, opts)?;
    d.dir = dir.to_path_buf();
    Ok(d)
}

/// [`diagnose`] of fields already read (or held in memory: [`RunFields::new`]).
pub fn diagnose_fields(fields: &mut RunFields, closure_args: &[String], opts: Options) -> anyhow::Result<Diagnosis> {
    if !(opts.phi_min.is_finite() && (0.0..1.0).contains(&opts.phi_min)) {
        bail!("--phi-min {}: allowed a volume fraction in [0, 1)", opts.phi_min);
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
        out.push(ClosureDiagnosis { label: n.label, model, comparisons, g0_fit });
    }
    let dir = fields.profiles_path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    Ok(Diagnosis { dir, cells: fields.rows(), phi_min: opts.phi_min, closures: out })
}

impl Diagnosis {
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
        s
    }
}
