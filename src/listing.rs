//! `saltus models`: every registered model per family with its equation, source,
//! parameters, defaults and valid ranges, and its string options with their allowed values.

use std::fmt::Write;

use anyhow::Context;
use saltus_core::closure::Family;
use saltus_core::{registry, runtime, Choice, Describe};

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
        let compiled = registry::models_of(f).into_iter().map(|m| ((m.default)(), (m.default_toml)()));
        let at_run_time = runtime::models(Some(f)).into_iter().map(|m| {
            let toml = runtime_toml(&m);
            (Box::new((*m).clone()) as Box<dyn Describe>, toml)
        });
        for (d, toml) in compiled.chain(at_run_time) {
            let _ = writeln!(s, "  {}", d.name());
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
            if let Ok(t) = toml {
                let inline = t.lines().filter(|l| !l.trim().is_empty()).collect::<Vec<_>>().join("; ");
                let _ = writeln!(s, "      toml:     {inline}");
            }
        }
        s.push('\n');
    }
    s
}

/// The TOML table of a run-time closure's default instance, as a compiled model's
/// `default_toml`.
fn runtime_toml(m: &runtime::RuntimeModel) -> Result<String, String> {
    let mut t = toml::Table::new();
    t.insert("type".into(), toml::Value::String(m.name.into()));
    for p in &m.params {
        t.insert(p.name.clone(), toml::Value::Float(p.value));
    }
    toml::to_string(&t).map_err(|e| e.to_string())
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
    let compiled = registry::models().into_iter().map(|m| (m.family, (m.default)(), false));
    let at_run_time =
        runtime::models(family).into_iter().map(|m| (m.family, Box::new((*m).clone()) as Box<dyn Describe>, true));
    for (model_family, d, registered_at_run_time) in compiled.chain(at_run_time) {
        if family.is_some_and(|f| f != model_family) {
            continue;
        }
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
        let mut entry = serde_json::json!({
            "family": model_family.key(), "name": d.name(), "equation": d.equation(),
            "source": d.source(), "parameters": params, "options": options
        });
        if registered_at_run_time {
            entry["runtime"] = serde_json::Value::Bool(true);
        }
        out.push(entry);
    }
    serde_json::Value::Array(out)
}
