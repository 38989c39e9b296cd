//! The granular closures `diagnose` evaluates: those of `--closures` (TOML text or a
//! file), else the scene's `[closures.granular]`, else the library's defaults.

use std::path::Path;

use anyhow::{bail, Context};
use saltus_core::closure::Family;
use saltus_core::registry;
use saltus_core::scene::{granular_from_value, Particles, Scene};
use saltus_core::GranularStress;

/// A closure with the label its comparisons carry.
#[derive(Debug)]
pub struct Named {
    /// label: the name of its table in a `--closures` document, else its model name
    pub label: String,
    /// the closure, with the grains' restitution and friction where it sets none
    pub closure: Box<dyn GranularStress>,
}

/// The closures of one `--closures` argument: a file when `arg` names one, else TOML text.
/// Accepted forms: one closure table (`type = "mu_i"`, or inline `{ type = "mu_i" }`), a
/// document with a `[closures.granular]` table (a scene), or named tables each holding
/// one closure (`[initial]`, `[proposed]`, ...), labelled by their names.
pub fn parse(arg: &str, particles: &Particles) -> anyhow::Result<Vec<Named>> {
    let path = Path::new(arg);
    let (text, origin) = if path.is_file() {
        let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
        (text, path.display().to_string())
    } else if arg.trim_end().ends_with(".toml") && !arg.contains('=') {
        bail!("{arg}: no such closures file (--closures takes a TOML table or a file holding one)");
    } else {
        (arg.to_string(), "--closures".to_string())
    };
    let mut table = crate::eval::parse_table_from(&text, &origin)?;
    let file = Path::new(&origin);
    let build = |v: toml::Value, key: &str| granular_from_value(v, particles, file, key);
    let named = |closure: Box<dyn GranularStress>| Named { label: closure.name().to_string(), closure };
    if table.contains_key("type") {
        return Ok(vec![named(build(toml::Value::Table(table), "closures.granular")?)]);
    }
    if let Some(closures) = table.remove("closures") {
        let granular = match closures {
            toml::Value::Table(mut t) => t.remove("granular"),
            _ => None,
        };
        let Some(g) = granular else {
            bail!("{origin}: key `closures.granular`: missing; this document has a [closures] table without one");
        };
        return Ok(vec![named(build(g, "closures.granular")?)]);
    }
    if table.is_empty() {
        bail!("{origin}: no closure; give a granular closure table such as `type = \"mu_i\"`, a [closures.granular] table, or named tables of them");
    }
    let mut out = Vec::new();
    for (key, value) in table {
        if !value.is_table() {
            bail!(
                "{origin}: key `{key}`: expected a granular closure table (with `type`), found {}; allowed: one closure \
                 table, a [closures.granular] table, or named tables each holding one closure",
                value.type_str()
            );
        }
        out.push(Named { label: key.clone(), closure: build(value, &key)? });
    }
    Ok(out)
}

/// The closures to evaluate: every `--closures` argument's, else the scene's own, else
/// the default of every registered granular model (the run's grains' e and mu_p).
/// Labels are made unique by a numeric suffix.
pub fn select(args: &[String], scene: &mut Scene) -> anyhow::Result<Vec<Named>> {
    let mut out = Vec::new();
    for a in args {
        out.extend(parse(a, &scene.particles)?);
    }
    if out.is_empty() {
        if let Some(c) = scene.closures.granular.take() {
            out.push(Named { label: c.name().to_string(), closure: c });
        }
    }
    if out.is_empty() {
        for m in registry::models_of(Family::Granular) {
            let mut t = toml::Table::new();
            t.insert("type".into(), toml::Value::String(m.name.to_string()));
            let closure = granular_from_value(toml::Value::Table(t), &scene.particles, Path::new("defaults"), m.name)?;
            out.push(Named { label: m.name.to_string(), closure });
        }
    }
    let mut seen: Vec<String> = Vec::new();
    for n in &mut out {
        let base = n.label.clone();
        let mut k = 2;
        while seen.contains(&n.label) {
            n.label = format!("{base}_{k}");
            k += 1;
        }
        seen.push(n.label.clone());
    }
    Ok(out)
}
