//! `saltus closure check`: the generic property checks every closure of saltus passes, run
//! on any registered model (ours or one linked from a user's crate).
//!
//! Checks, in order: every parameter and option documented (description, unit, range;
//! every key of the TOML table listed); TOML round trip; finite output over the declared
//! parameter ranges and the family's input ranges; batch methods equal to the scalar ones;
//! each limit the model declares ([`saltus_core::Limit`]). The random checks run
//! proptest's [`TestRunner`] with a fixed seed (the same report on every run) and shrink a
//! failing case: the report gives the smallest failing input found with the values.
//!
//! Inputs drawn per family: drag Re_p in [1e-6, 1e6] (log-uniform); hindrance phi in
//! [0, 0.6] and Re_p as for drag; viscosity phi in [0, 0.999 phi_limit); local granular
//! rheology I or K in [1e-8, 1e3]; kinetic theory phi in [0, 0.999 phi_max); turbulence a
//! 20-cell column 0.1 m high with a bed of volume fraction phi_bed; fluctuation k, omega,
//! nu_t, the Reynolds stress, slip, response time, depth and bulk velocity in ranges of
//! open-channel flows. Parameters are drawn one at a time within their declared ranges
//! (unbounded ends cut at 10 times the given value), the others at their given values; a
//! draw that breaks a constraint between parameters is discarded.

use std::fmt::Write as _;
use std::path::Path;

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use saltus_core::closure::Family;
use saltus_core::param::{number, Bound};
use saltus_core::{ColumnView, FlowScales, Limit, Param, ParticleSlip, Turbulence, TurbulencePoint};

use crate::eval::AnyClosure;

/// Parse a model given on the command line: `key = value` lines or an inline table
/// `{ type = "...", ... }`.
pub fn parse_model(text: &str) -> anyhow::Result<toml::Value> {
    let table = crate::eval::parse_table(text)?;
    if !table.contains_key("type") {
        anyhow::bail!("--model: no `type`; e.g. --model 'type = \"dallavalle\"' (see `saltus models`)");
    }
    Ok(toml::Value::Table(table))
}

/// Settings of a check run.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// random cases per property check
    pub cases: u32,
}

impl Default for Options {
    fn default() -> Self {
        Self { cases: 256 }
    }
}

/// Result of one check.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// short name, e.g. `finite` or `limit stokes`
    pub name: String,
    /// whether it passed
    pub passed: bool,
    /// what was checked (pass) or what went wrong (fail), one line
    pub summary: String,
    /// the smallest failing input found (parameters and inputs), on failure
    pub input: Option<String>,
}

/// Every check of one model.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// family checked
    pub family: Family,
    /// model name
    pub model: String,
    /// one outcome per check, in order
    pub outcomes: Vec<Outcome>,
}

impl Report {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.outcomes.iter().all(|o| o.passed)
    }

    /// Number of failed checks.
    pub fn failures(&self) -> usize {
        self.outcomes.iter().filter(|o| !o.passed).count()
    }

    /// The report as text, one line per check and the failing input under a failure.
    pub fn text(&self) -> String {
        let mut s = format!("closure check: {} model `{}`\n", self.family, self.model);
        for o in &self.outcomes {
            let _ = writeln!(s, "  {}  {:<20} {}", if o.passed { "pass" } else { "FAIL" }, o.name, o.summary);
            if let Some(i) = &o.input {
                let _ = writeln!(s, "        minimal failing input: {i}");
            }
        }
        let n = self.outcomes.len();
        match self.failures() {
            0 => {
                let _ = writeln!(s, "all {n} checks passed");
            }
            f => {
                let _ = writeln!(s, "{f} of {n} checks failed");
            }
        }
        s
    }
}

/// The error `saltus closure check` ends with when a check fails (exit code 1).
#[derive(Debug)]
pub struct ChecksFailed {
    /// failed checks
    pub failures: usize,
    /// model name
    pub model: String,
}

impl std::fmt::Display for ChecksFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {} check(s) failed (see the report above)", self.model, self.failures)
    }
}

impl std::error::Error for ChecksFailed {}

/// A model of any family, built from its table as `--model` gives it.
type Built = AnyClosure;

fn built(family: Family, table: &toml::Table) -> anyhow::Result<Built> {
    AnyClosure::build(family, toml::Value::Table(table.clone()), Path::new("--model"), "model")
}

/// Run every check on `model` (a closure table with its `type`) of `family`. An error is
/// bad input (unknown model, bad key or value), not a failed check.
pub fn check(family: Family, model: toml::Value, opts: Options) -> anyhow::Result<Report> {
    let toml::Value::Table(table) = model else { anyhow::bail!("--model: expected a TOML table") };
    let built = built(family, &table)?;
    let d = built.describe();
    d.validate().map_err(|e| anyhow::anyhow!("--model: {e}"))?;
    let space = ParamSpace { table: table.clone(), params: d.params() };
    let mut outcomes = vec![documented(&built), round_trip(&space, family, opts)];
    outcomes.push(finite(&space, family, opts));
    outcomes.push(batch(&space, family, opts));
    for (i, limit) in d.limits().into_iter().enumerate() {
        outcomes.push(declared_limit(&space, family, i, limit, opts));
    }
    Ok(Report { family, model: d.name().to_string(), outcomes })
}

fn pass(name: &str, summary: impl Into<String>) -> Outcome {
    Outcome { name: name.into(), passed: true, summary: summary.into(), input: None }
}

fn fail(name: &str, summary: impl Into<String>, input: Option<String>) -> Outcome {
    Outcome { name: name.into(), passed: false, summary: summary.into(), input }
}

/// Every key of a TOML table, dotted for sub-tables, `type` of the top level left out.
fn keys(t: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in t {
        let key = saltus_core::param::join_key(prefix, k);
        match v {
            toml::Value::Table(sub) => keys(sub, &key, out),
            _ if prefix.is_empty() && k == "type" => {}
            _ => out.push(key),
        }
    }
}

fn documented(m: &Built) -> Outcome {
    const NAME: &str = "documented";
    let d = m.describe();
    let (params, choices) = (d.params(), d.choices());
    let mut problems = Vec::new();
    if d.source().trim().is_empty() || d.equation().trim().is_empty() {
        problems.push("the model has no source or no equation".to_string());
    }
    for p in &params {
        if p.doc.trim().is_empty() {
            problems.push(format!("`{}` has no description", p.name));
        }
        if p.unit.trim().is_empty() {
            problems.push(format!("`{}` has no unit (\"-\" when dimensionless)", p.name));
        }
        if p.range.lo == Bound::Unbounded && p.range.hi == Bound::Unbounded {
            problems.push(format!("`{}` has no range", p.name));
        }
    }
    for c in &choices {
        if c.doc.trim().is_empty() {
            problems.push(format!("option `{}` has no description", c.name));
        }
        if !c.allowed.contains(&c.value.as_str()) {
            problems.push(format!("option `{}` = {} is not among its allowed values", c.name, c.value));
        }
    }
    let listed: Vec<&str> =
        params.iter().map(|p| p.name.as_str()).chain(choices.iter().map(|c| c.name.as_str())).collect();
    let mut table_keys = Vec::new();
    match m.to_toml().and_then(|t| t.parse::<toml::Table>().map_err(|e| e.to_string())) {
        Ok(t) => keys(&t, "", &mut table_keys),
        Err(e) => problems.push(format!("not serialisable: {e}")),
    }
    for k in &table_keys {
        if !listed.contains(&k.as_str()) {
            problems.push(format!("TOML key `{k}` is neither a listed parameter nor an option"));
        }
    }
    if problems.is_empty() {
        pass(
            NAME,
            format!(
                "{} parameters, {} options, {} TOML keys: each described, with unit and range",
                params.len(),
                choices.len(),
                table_keys.len()
            ),
        )
    } else {
        fail(NAME, problems.join("; "), None)
    }
}

/// The parameters of the model as given, their ranges, and how to set them in its table.
struct ParamSpace {
    table: toml::Table,
    params: Vec<Param>,
}

impl ParamSpace {
    /// One parameter at a time across its range, the others at their given values; a
    /// quarter of the draws keep every given value. Drawing all at once would mostly test
    /// corners where several parameters sit at extremes together (Fry 2024's exponent
    /// then exceeds 1000), which no declared range promises.
    fn strategy(&self) -> BoxedStrategy<Vec<f64>> {
        let given: Vec<f64> = self.params.iter().map(|p| p.value).collect();
        if self.params.is_empty() {
            return Just(given).boxed();
        }
        let ranges: Vec<BoxedStrategy<f64>> = self
            .params
            .iter()
            .map(|p| {
                let (lo, hi) = sample_interval(p);
                (lo..=hi).boxed()
            })
            .collect();
        let n = self.params.len();
        let one = (0..n, ranges).prop_map({
            let given = given.clone();
            move |(i, v)| {
                let mut g = given.clone();
                g[i] = v[i];
                g
            }
        });
        prop_oneof![1 => Just(given), 3 => one].boxed()
    }

    fn table_with(&self, values: &[f64]) -> toml::Table {
        let mut t = self.table.clone();
        for (p, &v) in self.params.iter().zip(values) {
            set(&mut t, &p.name, v);
        }
        t
    }

    fn describe_values(&self, values: &[f64]) -> String {
        let changed: Vec<String> = self
            .params
            .iter()
            .zip(values)
            .filter(|(p, v)| p.value.to_bits() != v.to_bits())
            .map(|(p, v)| format!("{} = {}", p.name, number(*v)))
            .collect();
        if changed.is_empty() {
            "parameters as given".into()
        } else {
            changed.join(", ")
        }
    }
}

/// A finite interval inside the range of `p` to draw from.
fn sample_interval(p: &Param) -> (f64, f64) {
    let scale = if p.value == 0.0 { 1.0 } else { 10.0 * p.value.abs() };
    let nudge = |x: f64| 1e-9 * x.abs().max(1e-300);
    let lo = match p.range.lo {
        Bound::Closed(a) => a,
        Bound::Open(a) => a + nudge(a).max(1e-9 * scale),
        Bound::Unbounded => -scale,
    };
    let hi = match p.range.hi {
        Bound::Closed(b) => b,
        Bound::Open(b) => b - nudge(b).max(1e-9 * scale.min(b.abs().max(1e-300))),
        Bound::Unbounded => scale.max(lo + scale),
    };
    // an unbounded end far from the default (f64::MAX) would put every draw out there
    let hi = hi.min(lo.abs().max(scale) * 1e3 + lo.max(0.0));
    if hi > lo {
        (lo, hi)
    } else {
        (lo, lo)
    }
}

/// Set dotted key `key` of `t` to `v`.
fn set(t: &mut toml::Table, key: &str, v: f64) {
    match key.split_once('.') {
        Some((head, rest)) => {
            if let Some(toml::Value::Table(sub)) = t.get_mut(head) {
                set(sub, rest, v);
            }
        }
        None => {
            t.insert(key.to_string(), toml::Value::Float(v));
        }
    }
}

fn runner(cases: u32) -> TestRunner {
    let config = Config {
        cases,
        max_global_rejects: cases.saturating_mul(50).max(1000),
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha))
}

/// Names of the inputs drawn by [`inputs`] for the finite and batch checks.
fn input_names(family: Family) -> &'static [&'static str] {
    match family {
        Family::Drag => &["re_p"],
        Family::Hindrance => &["phi", "re_p"],
        Family::Viscosity => &["phi/phi_limit"],
        Family::Granular => &["control number (I or K) or phi/phi_max"],
        Family::Turbulence => &["d", "phi_bed", "dudz"],
        Family::Fluctuation => {
            &["k", "omega", "nu_t", "reynolds_stress", "slip", "response_time", "depth", "bulk_velocity"]
        }
    }
}

fn log_uniform(lo: f64, hi: f64) -> BoxedStrategy<f64> {
    (lo.log10()..=hi.log10()).prop_map(|l| 10f64.powf(l)).boxed()
}

fn reynolds() -> BoxedStrategy<f64> {
    log_uniform(1e-6, 1e6)
}

/// The family's inputs, one draw.
fn inputs(family: Family) -> BoxedStrategy<Vec<f64>> {
    let v: Vec<BoxedStrategy<f64>> = match family {
        Family::Drag => vec![reynolds()],
        Family::Hindrance => vec![(0.0..=0.6).boxed(), reynolds()],
        Family::Viscosity => vec![(0.0..0.999).boxed()],
        Family::Granular => vec![log_uniform(1e-8, 1e3)],
        Family::Turbulence => vec![log_uniform(1e-5, 1e-2), (0.0..=0.6).boxed(), (0.0..=100.0).boxed()],
        Family::Fluctuation => vec![
            (0.0..=1.0).boxed(),
            log_uniform(1e-3, 1e3),
            (0.0..=1e-2).boxed(),
            (0.0..=1.0).boxed(),
            (0.0..=1.0).boxed(),
            log_uniform(1e-4, 10.0),
            log_uniform(1e-3, 1.0),
            log_uniform(1e-3, 5.0),
        ],
    };
    v.boxed()
}

fn show_inputs(family: Family, x: &[f64]) -> String {
    input_names(family).iter().zip(x).map(|(n, v)| format!("{n} = {}", number(*v))).collect::<Vec<_>>().join(", ")
}

/// Run `prop` over parameters × `input`; a failure becomes the shrunk input and message.
fn run_property<I: std::fmt::Debug + Clone>(
    name: &str,
    (space, family, opts): (&ParamSpace, Family, Options),
    input: BoxedStrategy<I>,
    show: impl Fn(&I) -> String,
    prop: impl Fn(&Built, &I) -> Result<(), String>,
    summary: String,
) -> Outcome {
    let mut r = runner(opts.cases);
    let strategy = (space.strategy(), input);
    let result = r.run(&strategy, |(values, x)| {
        let built = built(family, &space.table_with(&values))
            .map_err(|e| TestCaseError::reject(format!("parameters refused: {e}")))?;
        if built.describe().validate().is_err() {
            return Err(TestCaseError::reject("constraint between parameters"));
        }
        prop(&built, &x).map_err(TestCaseError::fail)
    });
    match result {
        Ok(()) => pass(name, summary),
        Err(TestError::Fail(why, (values, x))) => {
            let shown = show(&x);
            let input = if shown.is_empty() {
                space.describe_values(&values)
            } else {
                format!("{shown}; {}", space.describe_values(&values))
            };
            fail(name, why.message().to_string(), Some(input))
        }
        Err(TestError::Abort(why)) => fail(name, format!("no valid case could be drawn: {}", why.message()), None),
    }
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn round_trip(space: &ParamSpace, family: Family, opts: Options) -> Outcome {
    run_property(
        "toml round trip",
        (space, family, opts),
        Just(()).boxed(),
        |_| String::new(),
        |m, _| {
            let text = m.to_toml()?;
            let table: toml::Table = text.parse().map_err(|e: toml::de::Error| format!("{e}\n{text}"))?;
            let back = built(family, &table).map_err(|e| format!("its own TOML is refused: {e:#}\n{text}"))?;
            let again = back.to_toml()?;
            if again != text {
                return Err(format!("serialised twice differs:\n{text}\n---\n{again}"));
            }
            if back.describe().params() != m.describe().params() {
                return Err("parameters differ after the round trip".into());
            }
            Ok(())
        },
        "serialise, parse back, serialise again: same text and parameters".into(),
    )
}

fn finite_or(what: &str, v: f64) -> Result<(), String> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} = {}", number(v)))
    }
}

/// The 20-cell column of the turbulence checks: a bed of volume fraction `phi_bed` over
/// the lowest 2 cm, clear fluid above, uniform shear `dudz`.
struct Column {
    z: Vec<f64>,
    dz: Vec<f64>,
    phi: Vec<f64>,
    dudz: Vec<f64>,
    k: Vec<f64>,
    omega: Vec<f64>,
}

impl Column {
    fn new(phi_bed: f64, dudz: f64) -> Self {
        let n = 20;
        let dz = 0.1 / n as f64;
        let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * dz).collect();
        let phi = z.iter().map(|&z| if z < 0.02 { phi_bed } else { 0.0 }).collect();
        Self { dz: vec![dz; n], phi, dudz: vec![dudz; n], k: vec![1e-4; n], omega: vec![10.0; n], z }
    }
}

fn turbulence_eval(m: &dyn Turbulence, x: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let c = Column::new(x[1], x[2]);
    let transported: Vec<&[f64]> = match m.transported().len() {
        0 => Vec::new(),
        _ => vec![&c.k, &c.omega],
    };
    let col = ColumnView {
        z: &c.z,
        dz: &c.dz,
        phi: &c.phi,
        dudz: &c.dudz,
        diameter: x[0],
        nu_f: 1e-6,
        transported: &transported,
    };
    let mut lm = vec![0.0; c.z.len()];
    m.mixing_length(&col, &mut lm);
    let mut nut = vec![0.0; c.z.len()];
    m.eddy_viscosity(&col, &mut nut);
    let point = match m.as_two_equation() {
        Some(te) => c.k.iter().zip(&c.omega).map(|(&k, &w)| te.eddy_viscosity_of(k.max(0.0), w, col.nu_f)).collect(),
        None => lm.iter().zip(&c.dudz).map(|(&l, &g)| m.eddy_viscosity_point(l, g)).collect(),
    };
    (lm, nut, point)
}

fn fluctuation_point(x: &[f64]) -> (TurbulencePoint, ParticleSlip, FlowScales) {
    (
        TurbulencePoint { k: x[0], omega: x[1], nu_t: x[2], reynolds_stress: x[3] },
        ParticleSlip { slip: x[4], response_time: x[5] },
        FlowScales { depth: x[6], bulk_velocity: x[7] },
    )
}

fn finite_at(m: &Built, x: &[f64]) -> Result<(), String> {
    match m {
        Built::Drag(m) => {
            finite_or("C_D", m.cd(x[0]))?;
            finite_or("C_D Re_p", m.cd_re(x[0]))
        }
        Built::Hindrance(m) => finite_or("f", m.factor(x[0], x[1])),
        Built::Viscosity(m) => {
            let phi = x[0] * m.phi_limit().min(1.0);
            finite_or(&format!("nu_eff/nu_f at phi = {}", number(phi)), m.ratio(phi))
        }
        Built::Granular(m) => {
            if let Some(l) = m.as_local() {
                finite_or("mu", l.friction(x[0]))?;
                finite_or("phi", l.packing(x[0]))
            } else if let Some(k) = m.as_kinetic() {
                let phi = (x[0] / 1e3).min(0.999) * k.phi_max();
                let c = k.coefficients(phi, None);
                for (n, v) in [("g0", c.g0), ("F1", c.f1), ("F2", c.f2), ("F3", c.f3), ("F4", c.f4), ("e_eff", c.e_eff)]
                {
                    finite_or(&format!("{n} at phi = {}", number(phi)), v)?;
                }
                Ok(())
            } else {
                Err("neither a local rheology nor a kinetic theory".into())
            }
        }
        Built::Turbulence(m) => {
            let (lm, nut, _) = turbulence_eval(m.as_ref(), x);
            for (i, (l, n)) in lm.iter().zip(&nut).enumerate() {
                finite_or(&format!("l_m of cell {i}"), *l)?;
                finite_or(&format!("nu_t of cell {i}"), *n)?;
            }
            Ok(())
        }
        Built::Fluctuation(m) => {
            let (t, p, s) = fluctuation_point(x);
            finite_or("diffusivity", m.diffusivity(&t, &s))?;
            let mut rng = saltus_core::rng::stream(0, 0);
            let d = m.draw(&t, &p, &s, &mut rng);
            for (n, v) in ["u_x", "u_y", "u_z"].iter().zip(d.u) {
                finite_or(n, v)?;
            }
            // +inf is the documented duration of a closure that draws nothing
            if d.duration.is_nan() || d.duration < 0.0 {
                return Err(format!("duration = {}", number(d.duration)));
            }
            Ok(())
        }
    }
}

fn finite(space: &ParamSpace, family: Family, opts: Options) -> Outcome {
    let ranges = match family {
        Family::Drag => "Re_p in [1e-6, 1e6]",
        Family::Hindrance => "phi in [0, 0.6], Re_p in [1e-6, 1e6]",
        Family::Viscosity => "phi in [0, 0.999 phi_limit)",
        Family::Granular => "I or K in [1e-8, 1e3] (kinetic theory: phi below phi_max)",
        Family::Turbulence => "d in [1e-5, 1e-2] m, phi_bed in [0, 0.6], dudz in [0, 100] 1/s",
        Family::Fluctuation => "turbulence, slip and flow scales of open-channel flows",
    };
    run_property(
        "finite",
        (space, family, opts),
        inputs(family),
        |x| show_inputs(family, x),
        |m, x| finite_at(m, x),
        format!("{} cases: finite output for {ranges}, parameters within their ranges", opts.cases),
    )
}

fn batch_at(m: &Built, xs: &[Vec<f64>]) -> Result<(), String> {
    let col = |i: usize| xs.iter().map(|x| x[i]).collect::<Vec<f64>>();
    let cmp = |what: &str, batch: &[f64], scalar: &[f64]| -> Result<(), String> {
        for (i, (b, s)) in batch.iter().zip(scalar).enumerate() {
            if !same(*b, *s) {
                return Err(format!("{what}: batch {} != scalar {} at point {i}", number(*b), number(*s)));
            }
        }
        Ok(())
    };
    let n = xs.len();
    let mut out = vec![0.0; n];
    match m {
        Built::Drag(m) => {
            let re = col(0);
            m.cd_batch(&re, &mut out);
            cmp("C_D", &out, &re.iter().map(|&r| m.cd(r)).collect::<Vec<_>>())?;
            m.cd_re_batch(&re, &mut out);
            cmp("C_D Re_p", &out, &re.iter().map(|&r| m.cd_re(r)).collect::<Vec<_>>())
        }
        Built::Hindrance(m) => {
            let (phi, re) = (col(0), col(1));
            m.factor_batch(&phi, &re, &mut out);
            cmp("f", &out, &phi.iter().zip(&re).map(|(&p, &r)| m.factor(p, r)).collect::<Vec<_>>())
        }
        Built::Viscosity(m) => {
            let phi: Vec<f64> = col(0).iter().map(|u| u * m.phi_limit().min(1.0)).collect();
            m.ratio_batch(&phi, &mut out);
            cmp("nu_eff/nu_f", &out, &phi.iter().map(|&p| m.ratio(p)).collect::<Vec<_>>())
        }
        Built::Granular(m) => {
            let x = col(0);
            if let Some(l) = m.as_local() {
                let mut phi = vec![0.0; n];
                l.eval_batch(&x, &mut out, &mut phi);
                cmp("mu", &out, &x.iter().map(|&v| l.friction(v)).collect::<Vec<_>>())?;
                cmp("phi", &phi, &x.iter().map(|&v| l.packing(v)).collect::<Vec<_>>())?;
                let packing: Vec<f64> = x.iter().map(|&v| l.packing(v)).collect();
                l.control_of_packing_batch(&packing, &mut out);
                cmp("control_of_packing", &out, &packing.iter().map(|&p| l.control_of_packing(p)).collect::<Vec<_>>())
            } else if let Some(k) = m.as_kinetic() {
                let phi: Vec<f64> = x.iter().map(|v| (v / 1e3).min(0.999) * k.phi_max()).collect();
                let mut c = vec![saltus_core::KineticCoefficients::default(); n];
                k.coefficients_batch(&phi, None, &mut c);
                for (i, (b, &p)) in c.iter().zip(&phi).enumerate() {
                    let s = k.coefficients(p, None);
                    let pairs =
                        [(b.g0, s.g0), (b.f1, s.f1), (b.f2, s.f2), (b.f3, s.f3), (b.f4, s.f4), (b.e_eff, s.e_eff)];
                    if !pairs.iter().all(|(a, b)| same(*a, *b)) {
                        return Err(format!("coefficients: batch {b:?} != scalar {s:?} at point {i}"));
                    }
                }
                let cd: Vec<f64> = x.iter().map(|v| 0.4 + 24.0 / v.max(1e-300)).collect();
                k.drag_dissipation_batch(0.4, &cd, &mut out);
                cmp("c_J", &out, &cd.iter().map(|&c| k.drag_dissipation_factor(0.4, c)).collect::<Vec<_>>())
            } else {
                Err("neither a local rheology nor a kinetic theory".into())
            }
        }
        Built::Turbulence(m) => {
            for x in xs {
                let (_, nut, point) = turbulence_eval(m.as_ref(), x);
                cmp("nu_t (column vs point)", &nut, &point)?;
            }
            Ok(())
        }
        Built::Fluctuation(m) => {
            // one column shares its flow scales; the points differ
            let (_, _, s) = fluctuation_point(&xs[0]);
            let t: Vec<TurbulencePoint> = xs.iter().map(|x| fluctuation_point(x).0).collect();
            m.diffusivity_batch(&t, &s, &mut out);
            cmp("diffusivity", &out, &t.iter().map(|t| m.diffusivity(t, &s)).collect::<Vec<_>>())
        }
    }
}

fn batch(space: &ParamSpace, family: Family, opts: Options) -> Outcome {
    run_property(
        "batch = scalar",
        (space, family, opts),
        vec(inputs(family), 1..12).boxed(),
        |xs| xs.iter().map(|x| format!("[{}]", show_inputs(family, x))).collect::<Vec<_>>().join(" "),
        |m, xs| batch_at(m, xs),
        format!("{} cases of 1 to 11 points: every batch method equals its scalar method bit for bit", opts.cases),
    )
}

/// Whether the values `v_k` at `x_k` (towards the limit) tend to `target`: the last is
/// within 1e-3 (relative, absolute below 1), or the errors shrink geometrically (each at
/// most 0.9 times the previous: a slowly converging power law).
fn tends_to(what: &str, xs: &[f64], values: &[f64], target: f64) -> Result<(), String> {
    let err: Vec<f64> = values.iter().map(|v| (v - target).abs() / target.abs().max(1.0)).collect();
    let shown = || {
        xs.iter().zip(values).map(|(x, v)| format!("{} at {}", number(*v), number(*x))).collect::<Vec<_>>().join(", ")
    };
    if values.iter().any(|v| !v.is_finite()) {
        return Err(format!("{what} not finite on the way to the limit: {}", shown()));
    }
    let last = err.last().copied().unwrap_or(f64::INFINITY);
    let shrinking = err.windows(2).all(|w| w[1] <= 0.9 * w[0]);
    if last <= 1e-3 || shrinking {
        Ok(())
    } else {
        Err(format!("{what} does not tend to {}: {}", number(target), shown()))
    }
}

fn limit_name(l: Limit) -> (&'static str, String) {
    match l {
        Limit::Stokes { cd_re } => ("limit stokes", format!("C_D Re_p -> {} as Re_p -> 0", number(cd_re))),
        Limit::HighReynolds => ("limit high Re", "C_D -> cd_inf as Re_p -> inf".into()),
        Limit::Dilute => ("limit dilute", "factor -> 1 as phi -> 0".into()),
        Limit::Einstein { coefficient } => {
            ("limit einstein", format!("nu_eff/nu_f = 1 + {} phi + O(phi^2)", number(coefficient)))
        }
        Limit::Decreasing => ("decreasing", "main output non-increasing in its input".into()),
        Limit::Increasing => ("increasing", "main output non-decreasing in its input".into()),
        _ => ("limit", "unknown limit".into()),
    }
}

/// The limit `index` that the model declares, as declared by `m` itself: a limit may
/// depend on the parameters (Dallavalle's C_D Re_p -> a).
fn own_limit(m: &Built, index: usize) -> Result<Limit, String> {
    m.describe()
        .limits()
        .get(index)
        .copied()
        .ok_or_else(|| "the model declares fewer limits with these parameters".into())
}

fn declared_limit(space: &ParamSpace, family: Family, index: usize, limit: Limit, opts: Options) -> Outcome {
    let (name, what) = limit_name(limit);
    let small = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10];
    let large = [1e4, 1e6, 1e8, 1e10, 1e12];
    let applies = match limit {
        Limit::Stokes { .. } | Limit::HighReynolds => family == Family::Drag,
        Limit::Dilute => matches!(family, Family::Hindrance | Family::Viscosity),
        Limit::Einstein { .. } => family == Family::Viscosity,
        Limit::Decreasing | Limit::Increasing => {
            matches!(family, Family::Drag | Family::Hindrance | Family::Viscosity | Family::Granular)
        }
        _ => false,
    };
    if !applies {
        return fail(name, format!("declared, but it does not apply to the {family} family"), None);
    }
    let increasing = matches!(limit, Limit::Increasing);
    match limit {
        Limit::Decreasing | Limit::Increasing => {
            // two inputs x1 < x2 (and the other inputs shared)
            let pair: BoxedStrategy<Vec<f64>> = match family {
                Family::Drag => vec![reynolds(), log_uniform(1e-6, 1e2)].boxed(),
                Family::Hindrance => vec![(0.0..=0.6).boxed(), (0.0..=0.3).boxed(), reynolds()].boxed(),
                Family::Viscosity => vec![(0.0..0.999).boxed(), (0.0..=0.5).boxed()].boxed(),
                _ => vec![log_uniform(1e-8, 1e3), log_uniform(1e-6, 1e2)].boxed(),
            };
            let show = move |x: &Vec<f64>| match family {
                Family::Drag => format!("re_p = {}, re_p * (1 + {})", number(x[0]), number(x[1])),
                Family::Hindrance => {
                    format!("phi = {} and {}, re_p = {}", number(x[0]), number((x[0] + x[1]).min(0.9)), number(x[2]))
                }
                Family::Viscosity => {
                    format!("phi/phi_limit = {} and {}", number(x[0]), number((x[0] + x[1]).min(0.999)))
                }
                _ => format!("x = {}, x * (1 + {})", number(x[0]), number(x[1])),
            };
            let prop = move |m: &Built, x: &Vec<f64>| {
                let (a, b, x1, x2) = match m {
                    Built::Drag(m) => {
                        let x2 = x[0] * (1.0 + x[1]);
                        (m.cd(x[0]), m.cd(x2), x[0], x2)
                    }
                    Built::Hindrance(m) => {
                        let p2 = (x[0] + x[1]).min(0.9);
                        (m.factor(x[0], x[2]), m.factor(p2, x[2]), x[0], p2)
                    }
                    Built::Viscosity(m) => {
                        let lim = m.phi_limit().min(1.0);
                        let (p1, p2) = (x[0] * lim, (x[0] + x[1]).min(0.999) * lim);
                        (m.ratio(p1), m.ratio(p2), p1, p2)
                    }
                    Built::Granular(m) => match m.as_local() {
                        Some(l) => {
                            let x2 = x[0] * (1.0 + x[1]);
                            (l.friction(x[0]), l.friction(x2), x[0], x2)
                        }
                        None => return Err("monotonicity is checked on local rheologies (mu of I or K)".into()),
                    },
                    _ => return Err("not applicable".into()),
                };
                let slack = 1e-12 * a.abs().max(b.abs());
                let ok = if increasing { b >= a - slack } else { b <= a + slack };
                if ok {
                    Ok(())
                } else {
                    Err(format!("{} at {} then {} at {}", number(a), number(x1), number(b), number(x2)))
                }
            };
            run_property(name, (space, family, opts), pair, show, prop, format!("{what}: {} pairs", opts.cases))
        }
        _ => {
            let input: BoxedStrategy<Vec<f64>> =
                if family == Family::Hindrance { vec![reynolds()].boxed() } else { Just(Vec::new()).boxed() };
            let show = |x: &Vec<f64>| x.first().map_or_else(String::new, |r| format!("re_p = {}", number(*r)));
            let prop = move |m: &Built, x: &Vec<f64>| match (m, own_limit(m, index)?) {
                (Built::Drag(m), Limit::Stokes { cd_re }) => {
                    tends_to("C_D Re_p", &small, &small.map(|r| m.cd_re(r)), cd_re)
                }
                (Built::Drag(m), Limit::HighReynolds) => tends_to("C_D", &large, &large.map(|r| m.cd(r)), m.cd_inf()),
                (Built::Hindrance(m), Limit::Dilute) => tends_to("f", &small, &small.map(|p| m.factor(p, x[0])), 1.0),
                // towards 0 from inside the law's domain (phi_m of Krieger-Dougherty may be small)
                (Built::Viscosity(m), Limit::Dilute) => {
                    let phi = small.map(|p| p * m.phi_limit().min(1.0));
                    tends_to("nu_eff/nu_f", &phi, &phi.map(|p| m.ratio(p)), 1.0)
                }
                (Built::Viscosity(m), Limit::Einstein { coefficient }) => {
                    let phi = small.map(|p| p * m.phi_limit().min(1.0));
                    tends_to("(nu_eff/nu_f - 1)/phi", &phi, &phi.map(|p| (m.ratio(p) - 1.0) / p), coefficient)
                }
                _ => Err("not applicable".into()),
            };
            run_property(name, (space, family, opts), input, show, prop, what)
        }
    }
}
