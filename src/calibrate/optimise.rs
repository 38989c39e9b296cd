//! The minimisation: Levenberg-Marquardt (the MINPACK `lmder` trust-region algorithm of
//! Moré 1978, as the `levenberg-marquardt` crate implements it) on the misfit's residuals,
//! inside the bounds by the transformation of MINUIT (`bounds.rs`), u free. The Jacobian
//! is taken by central differences in p, its columns' runs in parallel, each run
//! warm-started from one anchor state so that every run is a function of its constants
//! alone.

use std::sync::Mutex;

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};
use rayon::prelude::*;

use super::bounds::{dp_du, to_p, to_u};
use super::model::{Fit, Problem};

/// The Jacobian of the residuals in p at `p` (central differences of `step` times each
/// bound's span, one-sided at a bound), its runs in parallel; the residuals at `p` come
/// with it. `free` selects the columns. `None` when a run fails on both sides.
pub fn jacobian(problem: &Problem, p: &[f64], free: &[usize], purpose: &str) -> Option<(DMatrix<f64>, Fit)> {
    let step = problem.cal.optimiser.step;
    let mut points: Vec<Vec<f64>> = vec![p.to_vec()];
    let mut widths = Vec::new();
    for &k in free {
        let [lo, hi] = problem.cal.parameters[k].bounds;
        let h = step * (hi - lo);
        let (a, b) = ((p[k] - h).max(lo + 1e-3 * h), (p[k] + h).min(hi - 1e-3 * h));
        let (mut minus, mut plus) = (p.to_vec(), p.to_vec());
        minus[k] = a;
        plus[k] = b;
        points.push(minus);
        points.push(plus);
        widths.push(b - a);
    }
    let fits: Vec<Option<Fit>> = points.par_iter().with_max_len(1).map(|q| problem.evaluate(q, purpose)).collect();
    let centre = fits[0].clone()?;
    let m = centre.residuals.len();
    let mut j = DMatrix::zeros(m, free.len());
    for (c, w) in widths.iter().enumerate() {
        let (minus, plus) = (&fits[1 + 2 * c], &fits[2 + 2 * c]);
        let column: Vec<f64> = match (minus, plus) {
            (Some(a), Some(b)) => (0..m).map(|i| (b.residuals[i] - a.residuals[i]) / w).collect(),
            (None, Some(b)) => (0..m).map(|i| (b.residuals[i] - centre.residuals[i]) / (w / 2.0)).collect(),
            (Some(a), None) => (0..m).map(|i| (centre.residuals[i] - a.residuals[i]) / (w / 2.0)).collect(),
            (None, None) => return None,
        };
        if column.len() != m {
            return None;
        }
        j.set_column(c, &DVector::from_vec(column));
    }
    Some((j, centre))
}

/// Why the minimisation stopped, in words.
pub fn reason(t: &TerminationReason, budget: bool) -> String {
    if budget {
        return "max_evaluations: the budget of model runs was spent".into();
    }
    match t {
        TerminationReason::Converged { ftol, xtol } => match (ftol, xtol) {
            (true, true) => "converged: relative reduction of the misfit and relative step below the tolerance",
            (true, false) => "converged: relative reduction of the misfit below the tolerance",
            _ => "converged: relative step below the tolerance",
        }
        .into(),
        TerminationReason::Orthogonal => "converged: the gradient of the misfit vanishes (gtol)".into(),
        TerminationReason::ResidualsZero => "converged: the misfit is zero".into(),
        TerminationReason::LostPatience => "max_evaluations: the optimiser's evaluation limit".into(),
        TerminationReason::NoImprovementPossible(w) => format!("converged at the machine precision ({w})"),
        TerminationReason::User(w) => format!("a model run failed where its {w} were needed"),
        TerminationReason::Numerical(w) => format!("a non-finite {w}"),
        other => format!("{other:?}"),
    }
}

/// The result of one minimisation.
#[derive(Clone, Debug)]
pub struct Minimum {
    /// every constant (the fixed ones at their values)
    pub params: Vec<f64>,
    /// the stopping reason, in words
    pub reason: String,
    /// whether it converged
    pub converged: bool,
    /// model runs it took
    pub evaluations: usize,
}

struct Target<'a> {
    problem: &'a Problem,
    /// every constant; the free ones are overwritten from `u`
    full: Vec<f64>,
    free: Vec<usize>,
    u: DVector<f64>,
    purpose: String,
    /// the best point seen: (misfit, constants)
    best: Mutex<(f64, Vec<f64>)>,
    /// runs left
    budget: Mutex<usize>,
    /// residuals a failed run stands for: larger than any accepted step's
    penalty: DVector<f64>,
}

impl Target<'_> {
    fn params(&self, u: &DVector<f64>) -> Vec<f64> {
        let mut p = self.full.clone();
        for (c, &k) in self.free.iter().enumerate() {
            p[k] = to_p(u[c], self.problem.cal.parameters[k].bounds);
        }
        p
    }

    fn spend(&self, n: usize) -> bool {
        let Ok(mut b) = self.budget.lock() else { return false };
        if *b < n {
            *b = 0;
            return false;
        }
        *b -= n;
        true
    }

    fn offer(&self, p: &[f64], f: &Fit) {
        let s: f64 = f.residuals.iter().map(|r| r * r).sum();
        if let Ok(mut best) = self.best.lock() {
            if s < best.0 {
                *best = (s, p.to_vec());
            }
        }
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Target<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, u: &DVector<f64>) {
        self.u.copy_from(u);
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        if !self.spend(1) {
            return None;
        }
        let p = self.params(&self.u);
        match self.problem.evaluate(&p, &self.purpose) {
            Some(f) => {
                self.offer(&p, &f);
                Some(DVector::from_vec(f.residuals))
            }
            // a failed run is a step not taken
            None => Some(self.penalty.clone()),
        }
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        if !self.spend(1 + 2 * self.free.len()) {
            return None;
        }
        let p = self.params(&self.u);
        let (j, centre) = jacobian(self.problem, &p, &self.free, &self.purpose)?;
        self.offer(&p, &centre);
        let mut j = j;
        for (c, &k) in self.free.iter().enumerate() {
            let s = dp_du(self.u[c], self.problem.cal.parameters[k].bounds);
            j.column_mut(c).scale_mut(s);
        }
        Some(j)
    }
}

/// Minimise the misfit over the constants `free` from `start` (the others held at their
/// values in `start`), within `budget` model runs.
pub fn minimise(problem: &Problem, start: &[f64], free: &[usize], budget: usize, purpose: &str) -> Option<Minimum> {
    let first = problem.evaluate(start, purpose)?;
    let s0: f64 = first.residuals.iter().map(|r| r * r).sum();
    let used_before = problem.log.lock().map_or(0, |l| l.len());
    if free.is_empty() {
        return Some(Minimum {
            params: start.to_vec(),
            reason: "nothing to fit".into(),
            converged: true,
            evaluations: 1,
        });
    }
    let scale = (s0.max(1.0)).sqrt() * 1e3 / (first.residuals.len() as f64).sqrt();
    let target = Target {
        problem,
        full: start.to_vec(),
        free: free.to_vec(),
        u: DVector::from_iterator(free.len(), free.iter().map(|&k| to_u(start[k], problem.cal.parameters[k].bounds))),
        purpose: purpose.to_string(),
        best: Mutex::new((s0, start.to_vec())),
        budget: Mutex::new(budget.saturating_sub(1)),
        penalty: DVector::from_element(first.residuals.len(), scale),
    };
    let tol = problem.cal.optimiser.tolerance;
    let lm = LevenbergMarquardt::new().with_ftol(tol).with_xtol(tol).with_gtol(1e-12).with_patience(budget.max(1));
    let (target, report) = lm.minimize(target);
    let spent = target.budget.lock().map_or(true, |b| *b == 0);
    let (_, params) = target.best.lock().ok()?.clone();
    let used = problem.log.lock().map_or(0, |l| l.len()) - used_before + 1;
    Some(Minimum {
        params,
        reason: reason(&report.termination, spent && !report.termination.was_successful()),
        converged: report.termination.was_successful(),
        evaluations: used,
    })
}
