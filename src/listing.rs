//! `saltus models`: every registered model per family with its equation, source,
//! parameters, defaults and valid ranges, and its string options with their allowed values.

use std::fmt::Write;

use anyhow::Context;
use saltus_core::closure::Family;
use saltus_core::{registry, Choice, Describe};

/// The scene family named `name` (`drag`, `hindrance`, ...); the error lists the known ones.
pub fn parse_family(name: &str) -> anyhow::Result<Family> {
    Family::from_key(name).with_context(|| {
        format!(
            "unknown family `{name}`; known: {}",
            Family::ALL.iter().map(|f| f.key()).collect::<Vec<_>>().join(", ")
        )
    })
}

/// Text listing of the models of `family` (all families when `None`).
pub fn text(family: Option<Family>) -> String {
    let mut s = String::new();
    for f in Family::ALL.into_iter().filter(|f| family.is_none_or(|g| g == *f)) {
        let _ = writeln!(s, "[closures.{}]  {}", f.key(), f.describe());
        for m in registry::models_of(f) {
            let d = (m.default)();
            let _ = writeln!(s, "  {}", m.name);
            let _ = writeln!(s, "      equation: {}", d.equation());
            let _ = writeln!(s, "      source:   {}", d.source());
            let params = d.params();
            let choices = d.choices();
            if params.is_empty() && choices.is_empty() {
                let _ = writeln!(s, "      parameters: none");
            }
            for p in params {
                let _ = writeln!(
                    s,
                    "      {:<22} default {:<10} range {:<14} [{}] {}",
                    p.name,
                    p.value,
                    p.range.to_string(),
                    p.unit,
                    p.doc
                );
            }
            for c in choices {
                let _ = writeln!(s, "{}", choice_line(&c));
            }
            if let Ok(t) = (m.default_toml)() {
                let inline = t.lines().filter(|l| !l.trim().is_empty()).collect::<Vec<_>>().join("; ");
                let _ = writeln!(s, "      toml:     {inline}");
            }
        }
        s.push('\n');
    }
    s
}

/// Parameters of a configured model as JSON objects: the keys of [`json`]'s `parameters`
/// plus `value`, the configured value (`default` is that of `defaults`, the registered
/// default instance, or null for a parameter it does not have, a nested model switched
/// to another type).
pub fn params_json(model: &dyn Describe, defaults: Option<&dyn Describe>) -> Vec<serde_json::Value> {
    let defaults = defaults.map(|d| d.params()).unwrap_or_default();
    model
        .params()
        .into_iter()
        .map(|p| {
            let default = defaults.iter().find(|d| d.name == p.name).map(|d| d.value);
            serde_json::json!({
                "name": p.name, "value": p.value, "default": default, "range": p.range.to_string(),
                "unit": p.unit, "doc": p.doc
            })
        })
        .collect()
}

/// The text line of a string option or switch: its allowed values in braces where a real
/// parameter shows its range.
pub fn choice_line(c: &Choice) -> String {
    format!("      {:<22} default {:<10} one of {{{}}} {}", c.name, c.value, c.allowed.join(", "), c.doc)
}

/// JSON listing (for tools).
pub fn json(family: Option<Family>) -> serde_json::Value {
    let mut out = Vec::new();
    for m in registry::models() {
        if family.is_some_and(|f| f != m.family) {
            continue;
        }
        let d = (m.default)();
        let params: Vec<_> = d
            .params()
            .into_iter()
            .map(|p| {
                serde_json::json!({
                    "name": p.name, "default": p.value, "range": p.range.to_string(),
                    "unit": p.unit, "doc": p.doc
                })
            })
            .collect();
        let options: Vec<_> = d
            .choices()
            .into_iter()
            .map(|c| serde_json::json!({"name": c.name, "default": c.value, "allowed": c.allowed, "doc": c.doc}))
            .collect();
        out.push(serde_json::json!({
            "family": m.family.key(), "name": m.name, "equation": d.equation(),
            "source": d.source(), "parameters": params, "options": options
        }));
    }
    serde_json::Value::Array(out)
}
