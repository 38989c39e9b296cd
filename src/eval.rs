//! `saltus closure eval`: evaluate one closure on the rows of a table.
//!
//! The input table's header names the closure's inputs; the output is the input columns
//! followed by the closure's outputs. Inputs a model does not need may be absent.

use std::path::Path;

use anyhow::{anyhow, bail, Context};
use saltus_core::closure::Family;
use saltus_core::runtime::Built;
use saltus_core::{registry, runtime};
use saltus_core::{ColumnView, Describe, Field, FlowScales, ParticleSlip, TurbulencePoint};

use crate::table::Table;

/// A family as seen by `closure eval`: the seven scene families plus `kinetic_theory`, the
/// kinetic part of a `frictional_collisional` granular table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EvalFamily {
    /// drag coefficient
    Drag,
    /// hindrance factor
    Hindrance,
    /// effective viscosity
    Viscosity,
    /// local granular rheology (mu_i, mu_k)
    Granular,
    /// kinetic-theory coefficients of a frictional_collisional table
    #[value(name = "kinetic_theory")]
    KineticTheory,
    /// mixing length and eddy viscosity over a column
    Turbulence,
    /// fluctuation diffusivity and one stochastic draw per row
    Fluctuation,
    /// friction factor of smooth side walls
    #[value(name = "wall_friction")]
    WallFriction,
}

impl EvalFamily {
    /// Input column names (required ones first; see [`EvalFamily::help`]).
    pub fn inputs(self) -> &'static [&'static str] {
        match self {
            // the names of a closure registered at run time, defined once
            EvalFamily::Drag | EvalFamily::Hindrance | EvalFamily::Viscosity | EvalFamily::WallFriction => {
                self.scene_family().and_then(runtime::io).map_or(&[], |(inputs, _)| inputs)
            }
            EvalFamily::Granular => &["i (mu_i) or k (mu_k)"],
            EvalFamily::KineticTheory => &["phi"],
            EvalFamily::Turbulence => &["z", "phi", "dudz", "d"],
            EvalFamily::Fluctuation => {
                &["k", "omega", "nu_t", "reynolds_stress", "slip", "response_time", "depth", "bulk_velocity"]
            }
        }
    }

    /// Every input name the family reads (a granular model reads `i` or `k`, a
    /// fluctuation model also `granular_temperature` when it needs it): names outside it
    /// are ignored by [`Model::outputs`].
    pub fn input_names(self) -> &'static [&'static str] {
        match self {
            EvalFamily::Granular => &["i", "k"],
            EvalFamily::Fluctuation => &[
                "k",
                "omega",
                "nu_t",
                "reynolds_stress",
                "granular_temperature",
                "slip",
                "response_time",
                "depth",
                "bulk_velocity",
            ],
            other => other.inputs(),
        }
    }

    /// Output column names.
    pub fn outputs(self) -> &'static [&'static str] {
        match self {
            EvalFamily::Drag | EvalFamily::Hindrance | EvalFamily::Viscosity => {
                self.scene_family().and_then(runtime::io).map_or(&[], |(_, outputs)| outputs)
            }
            EvalFamily::Granular => &["mu", "phi"],
            EvalFamily::KineticTheory => &["g0", "f1", "f2", "f3", "f4", "e_eff"],
            EvalFamily::Turbulence => &["l_m", "nu_t"],
            EvalFamily::Fluctuation => &["diffusivity", "u_x", "u_y", "u_z", "duration"],
            EvalFamily::WallFriction => &["f", "f_re"],
        }
    }

    /// Name on the command line.
    pub fn key(self) -> &'static str {
        match self {
            EvalFamily::KineticTheory => "kinetic_theory",
            other => other.scene_family().map_or("", Family::key),
        }
    }

    fn scene_family(self) -> Option<Family> {
        Some(match self {
            EvalFamily::Drag => Family::Drag,
            EvalFamily::Hindrance => Family::Hindrance,
            EvalFamily::Viscosity => Family::Viscosity,
            EvalFamily::Granular | EvalFamily::KineticTheory => Family::Granular,
            EvalFamily::Turbulence => Family::Turbulence,
            EvalFamily::Fluctuation => Family::Fluctuation,
            EvalFamily::WallFriction => Family::WallFriction,
        })
    }

    /// Every family, for help texts.
    pub const ALL: [EvalFamily; 8] = [
        EvalFamily::Drag,
        EvalFamily::Hindrance,
        EvalFamily::Viscosity,
        EvalFamily::Granular,
        EvalFamily::KineticTheory,
        EvalFamily::Turbulence,
        EvalFamily::Fluctuation,
        EvalFamily::WallFriction,
    ];

    /// Help paragraph listing every family's inputs and outputs.
    pub fn help() -> String {
        let mut s = String::from("Families, inputs -> outputs:\n");
        for f in Self::ALL {
            s.push_str(&format!("  {:<15} {} -> {}\n", f.key(), f.inputs().join(", "), f.outputs().join(", ")));
        }
        s.push_str(
            "\nNotes: hindrance re_p is the interstitial |u_f - v_p| d / nu; kinetic_theory takes a\n\
             frictional_collisional table (type may be omitted) and gives the coefficients with\n\
             saltation off, f4 with the effective restitution e_eff; turbulence rows are the cells\n\
             of one column ordered from the bottom wall (z = cell centres, faces half-way);\n\
             fluctuation inputs default to 0 except those the model needs; its draw uses --seed,\n\
             one stream per row; wall_friction re is |U| W / nu_f on the channel width W, f Re\n\
             the Poiseuille number (finite at re = 0).",
        );
        s
    }

    /// The family named `name` as on the command line (`kinetic_theory` included).
    pub fn from_key(name: &str) -> anyhow::Result<EvalFamily> {
        Self::ALL.into_iter().find(|f| f.key() == name).ok_or_else(|| {
            anyhow!(
                "unknown family `{name}`; known: {}",
                Self::ALL.iter().map(|f| f.key()).collect::<Vec<_>>().join(", ")
            )
        })
    }
}

/// Parse a model given on the command line: either `key = value` lines or an inline table
/// `{ type = "...", ... }`.
pub fn parse_model(text: &str, family: EvalFamily) -> anyhow::Result<toml::Value> {
    parse_model_from(text, family, "--model")
}

/// [`parse_model`] of a text that messages name `label`.
pub fn parse_model_from(text: &str, family: EvalFamily, label: &str) -> anyhow::Result<toml::Value> {
    Ok(model_table(parse_table_from(text, label)?, family))
}

/// A model's table as the family reads it: a `kinetic_theory` table is a
/// `frictional_collisional` granular table whose `type` may be left out.
pub fn model_table(mut table: toml::Table, family: EvalFamily) -> toml::Value {
    if family == EvalFamily::KineticTheory && !table.contains_key("type") {
        table.insert("type".into(), toml::Value::String("frictional_collisional".into()));
    }
    toml::Value::Table(table)
}

/// How messages name an input table and its rows: the CSV file with rows counted as its
/// lines (the first data row is line 2), or a caller's arrays indexed from 0.
#[derive(Clone, Copy, Debug)]
pub struct Rows<'a> {
    /// what the table came from, first word of every message
    pub origin: &'a str,
    /// number given to the first row
    pub first: usize,
}

impl<'a> Rows<'a> {
    /// Rows of a CSV file (or stdin) named `origin`: the first data row is its line 2.
    pub fn csv(origin: &'a str) -> Self {
        Rows { origin, first: 2 }
    }
}

/// One closure of an [`EvalFamily`], built from its TOML table and checked once, then
/// evaluated on any number of input tables ([`Model::outputs`]).
#[derive(Debug)]
pub struct Model {
    family: EvalFamily,
    kind: Built,
}

impl Model {
    /// Build `model` (a closure table) of `family`. Errors name `file` and the key path
    /// under `key` (`--model` and `model` on the command line).
    pub fn build(family: EvalFamily, model: toml::Value, file: &Path, key: &str) -> anyhow::Result<Model> {
        let f = family.scene_family().ok_or_else(|| anyhow!("unknown family"))?;
        let origin = file.display();
        let kind = Built::from_value(f, model, file, key)?;
        if let Built::Granular(m) = &kind {
            if family == EvalFamily::Granular && m.as_local().is_none() {
                bail!(
                    "{origin}: `{}` is not a local rheology; evaluate its coefficients with --family kinetic_theory",
                    m.name()
                );
            }
            if family == EvalFamily::KineticTheory && m.as_kinetic().is_none() {
                bail!("{origin}: `{}` is not a kinetic-theory closure (use frictional_collisional)", m.name());
            }
        }
        Ok(Model { family, kind })
    }

    /// The family the model was built for.
    pub fn family(&self) -> EvalFamily {
        self.family
    }

    /// The model's name, equation, source and parameters with their values.
    pub fn describe(&self) -> &dyn Describe {
        self.kind.describe()
    }

    /// The default instance of this model, as registered: its parameters' defaults.
    pub fn registered_default(&self) -> Option<Box<dyn Describe>> {
        let family = self.family.scene_family()?;
        let name = self.describe().name();
        match registry::models_of(family).into_iter().find(|m| m.name == name) {
            Some(m) => Some((m.default)()),
            None => runtime::lookup(family, name).map(|m| Box::new((*m).clone()) as Box<dyn Describe>),
        }
    }

    /// The family's output columns ([`EvalFamily::outputs`]) on the rows of `input`. Inputs
    /// are looked up by name; those a model does not need may be absent. The fluctuation
    /// draw of row i uses stream i of `seed`.
    pub fn outputs(&self, input: &Table, rows: Rows, seed: u64) -> anyhow::Result<Table> {
        let n = input.rows();
        let family = self.family;
        let origin = rows.origin;
        let mut out = Table::default();
        match &self.kind {
            Built::Drag(m) => {
                let re = need(input, "re_p", family, origin)?;
                check_reynolds(re, rows)?;
                let mut cd = vec![0.0; n];
                m.cd_batch(re, &mut cd);
                out.push("cd", cd);
            }
            Built::Hindrance(m) => {
                let phi = need(input, "phi", family, origin)?;
                let re = need(input, "re_p", family, origin)?;
                check_fraction(phi, rows)?;
                check_reynolds(re, rows)?;
                let mut f = vec![0.0; n];
                m.factor_batch(phi, re, &mut f);
                out.push("factor", f);
            }
            Built::Viscosity(m) => {
                let phi = need(input, "phi", family, origin)?;
                check_fraction(phi, rows)?;
                let mut r = vec![0.0; n];
                m.ratio_batch(phi, &mut r);
                out.push("nu_ratio", r);
            }
            Built::Granular(m) if family != EvalFamily::KineticTheory => {
                let local = m.as_local().ok_or_else(|| anyhow!("`{}` is not a local rheology", m.name()))?;
                let x = need(input, local.control_name(), family, origin)?;
                let mut mu = vec![0.0; n];
                let mut phi = vec![0.0; n];
                local.eval_batch(x, &mut mu, &mut phi);
                out.push("mu", mu);
                out.push("phi", phi);
            }
            Built::Granular(m) => {
                let kt = m.as_kinetic().ok_or_else(|| anyhow!("`{}` is not a kinetic-theory closure", m.name()))?;
                let phi = need(input, "phi", family, origin)?;
                check_fraction(phi, rows)?;
                let mut c = vec![saltus_core::KineticCoefficients::default(); n];
                kt.coefficients_batch(phi, None, &mut c);
                out.push("g0", c.iter().map(|c| c.g0).collect());
                out.push("f1", c.iter().map(|c| c.f1).collect());
                out.push("f2", c.iter().map(|c| c.f2).collect());
                out.push("f3", c.iter().map(|c| c.f3).collect());
                out.push("f4", c.iter().map(|c| c.f4).collect());
                out.push("e_eff", c.iter().map(|c| c.e_eff).collect());
            }
            Built::Turbulence(m) => {
                let z = need(input, "z", family, origin)?;
                let phi = need(input, "phi", family, origin)?;
                let dudz = need(input, "dudz", family, origin)?;
                check_fraction(phi, rows)?;
                let dz = cell_widths(z, origin)?;
                let d = need(input, "d", family, origin)?;
                let diameter = d.first().copied().unwrap_or(0.0);
                if d.iter().any(|&x| x != diameter) || diameter.is_nan() || diameter <= 0.0 {
                    bail!("{origin}: column `d` must hold one positive grain diameter (m) on every row");
                }
                let col = ColumnView { z, dz: &dz, phi, dudz, diameter, nu_f: 0.0, transported: &[] };
                let mut lm = vec![0.0; n];
                m.mixing_length(&col, &mut lm);
                let nut = lm.iter().zip(dudz).map(|(&l, &g)| m.eddy_viscosity_point(l, g)).collect();
                out.push("l_m", lm);
                out.push("nu_t", nut);
            }
            Built::Fluctuation(m) => {
                for f in m.needs().iter() {
                    let col = match f {
                        Field::Tke => "k",
                        Field::Omega => "omega",
                        Field::EddyViscosity => "nu_t",
                        Field::ReynoldsStress => "reynolds_stress",
                        Field::GranularTemperature => "granular_temperature",
                    };
                    need(input, col, family, origin).with_context(|| format!("model `{}` needs {f}", m.name()))?;
                }
                let (k, omega, nut, rs) = (
                    optional(input, "k"),
                    optional(input, "omega"),
                    optional(input, "nu_t"),
                    optional(input, "reynolds_stress"),
                );
                let (slip, tp) = (optional(input, "slip"), optional(input, "response_time"));
                let (depth, ub) = (optional(input, "depth"), optional(input, "bulk_velocity"));
                let mut cols: [Vec<f64>; 5] = Default::default();
                for i in 0..n {
                    let t = TurbulencePoint { k: k[i], omega: omega[i], nu_t: nut[i], reynolds_stress: rs[i] };
                    let s = FlowScales { depth: depth[i], bulk_velocity: ub[i] };
                    let p = ParticleSlip { slip: slip[i], response_time: tp[i] };
                    let mut rng = saltus_core::rng::stream(seed, i as u64);
                    let d = m.draw(&t, &p, &s, &mut rng);
                    cols[0].push(m.diffusivity(&t, &s));
                    cols[1].push(d.u[0]);
                    cols[2].push(d.u[1]);
                    cols[3].push(d.u[2]);
                    cols[4].push(d.duration);
                }
                for (name, c) in ["diffusivity", "u_x", "u_y", "u_z", "duration"].into_iter().zip(cols) {
                    out.push(name, c);
                }
            }
            Built::WallFriction(m) => {
                let re = need(input, "re", family, origin)?;
                check_non_negative("re", re, rows)?;
                let mut po = re.to_vec();
                m.poiseuille_batch(&mut po);
                // the model's own f: a frictionless wall has f = 0 at Re = 0 too
                out.push("f", re.iter().map(|&r| m.friction_factor(r)).collect());
                out.push("f_re", po);
            }
        }
        Ok(out)
    }
}

/// The TOML table of `--model`: `key = value` lines or an inline table `{ ... }`.
pub fn parse_table(text: &str) -> anyhow::Result<toml::Table> {
    parse_table_from(text, "--model")
}

/// [`parse_table`] of a text that messages name `label`.
pub fn parse_table_from(text: &str, label: &str) -> anyhow::Result<toml::Table> {
    let trimmed = text.trim();
    // some errors (a key without a value) carry no message of their own, only the span
    let syntax = |e: toml::de::Error| match e.message().trim() {
        "" => anyhow!("{label}: TOML syntax error: {}", e.to_string().trim()),
        m => anyhow!("{label}: TOML syntax error: {m}"),
    };
    if !trimmed.starts_with('{') {
        return trimmed.parse().map_err(syntax);
    }
    let mut t: toml::Table = format!("model = {trimmed}").parse().map_err(syntax)?;
    match t.remove("model") {
        Some(toml::Value::Table(inner)) => Ok(inner),
        _ => bail!("{label}: expected a table"),
    }
}

fn need<'a>(t: &'a Table, name: &str, family: EvalFamily, origin: &str) -> anyhow::Result<&'a [f64]> {
    t.get(name).ok_or_else(|| {
        anyhow!(
            "{origin}: missing input column `{name}`; family {} takes {} (found: {})",
            family.key(),
            family.inputs().join(", "),
            t.names.join(", ")
        )
    })
}

fn optional(t: &Table, name: &str) -> Vec<f64> {
    t.get(name).map_or_else(|| vec![0.0; t.rows()], <[f64]>::to_vec)
}

/// Evaluate `model` (a closure table) of `family` on the rows of a CSV named `origin`;
/// returns the input columns followed by the outputs.
pub fn evaluate(
    family: EvalFamily,
    model: toml::Value,
    input: &Table,
    origin: &str,
    seed: u64,
) -> anyhow::Result<Table> {
    let m = Model::build(family, model, Path::new("--model"), "model")?;
    let outputs = m.outputs(input, Rows::csv(origin), seed)?;
    let mut out = input.clone();
    for (name, c) in outputs.names.into_iter().zip(outputs.columns) {
        out.push(name, c);
    }
    Ok(out)
}

fn check_reynolds(re: &[f64], rows: Rows) -> anyhow::Result<()> {
    check_non_negative("re_p", re, rows)
}

/// Every value of column `name` finite and >= 0.
fn check_non_negative(name: &str, values: &[f64], rows: Rows) -> anyhow::Result<()> {
    if let Some((i, r)) = values.iter().enumerate().find(|(_, r)| !(r.is_finite() && **r >= 0.0)) {
        bail!("{}: row {}: {name} = {r}: allowed finite values >= 0", rows.origin, i + rows.first);
    }
    Ok(())
}

fn check_fraction(phi: &[f64], rows: Rows) -> anyhow::Result<()> {
    if let Some((i, p)) = phi.iter().enumerate().find(|(_, p)| !(0.0..1.0).contains(*p)) {
        bail!("{}: row {}: phi = {p} outside [0, 1)", rows.origin, i + rows.first);
    }
    Ok(())
}

/// Cell widths of a column given by its cell centres: faces half-way between centres,
/// the bottom face at z = 0.
pub fn cell_widths(z: &[f64], origin: &str) -> anyhow::Result<Vec<f64>> {
    let mut faces = Vec::with_capacity(z.len() + 1);
    faces.push(0.0);
    for w in z.windows(2) {
        if w[1] <= w[0] {
            bail!("{origin}: z must increase from row to row (cell centres from the bottom wall)");
        }
        faces.push(0.5 * (w[0] + w[1]));
    }
    if let Some(&last) = z.last() {
        let below = faces[faces.len() - 1];
        if last <= below {
            bail!("{origin}: z must be positive cell centres from the bottom wall");
        }
        faces.push(2.0 * last - below);
    }
    Ok(faces.windows(2).map(|f| f[1] - f[0]).collect())
}
