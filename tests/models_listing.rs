//! Identity test of the `#[derive(Describe)]` refactor: `saltus models` and
//! `saltus models --json` print what the hand-written `Describe` impls printed
//! (tests/fixtures/models_before.*, captured from the binary before the conversion), but
//! for the one intended change: string options and switches are listed with their allowed
//! values (text lines after the parameters, a JSON `options` array). The fixture follows
//! the closures' ranges as they are set (k-omega's `roughness` is [1e-3, 1e3] d).

mod common;

use common::{saltus, stdout};

/// Option lines that the fixture lacks, with the model each belongs to.
fn option_lines(json: &serde_json::Value) -> Vec<(String, String, String)> {
    let mut v = Vec::new();
    for m in json.as_array().expect("an array of models") {
        let name = m["name"].as_str().expect("name").to_string();
        let family = m["family"].as_str().expect("family").to_string();
        for o in m["options"].as_array().expect("options") {
            let allowed: Vec<&str> = o["allowed"].as_array().unwrap().iter().map(|a| a.as_str().unwrap()).collect();
            let line = format!(
                "      {:<22} default {:<10} one of {{{}}} {}",
                o["name"].as_str().unwrap(),
                o["default"].as_str().unwrap(),
                allowed.join(", "),
                o["doc"].as_str().unwrap()
            );
            v.push((family.clone(), name.clone(), line));
        }
    }
    v
}

#[test]
fn models_json_is_the_fixture_plus_options() {
    let o = saltus(&["models", "--json"]);
    assert!(o.status.success());
    let mut now: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let before: serde_json::Value = serde_json::from_str(include_str!("fixtures/models_before.json")).unwrap();
    for m in now.as_array_mut().unwrap() {
        let options = m.as_object_mut().unwrap().remove("options");
        assert!(options.is_some_and(|o| o.is_array()), "{m}");
    }
    assert_eq!(now, before);
}

#[test]
fn models_text_is_the_fixture_plus_option_lines() {
    let json: serde_json::Value = serde_json::from_str(&stdout(&saltus(&["models", "--json"]))).unwrap();
    let extra = option_lines(&json);
    let o = saltus(&["models"]);
    assert!(o.status.success());
    let now = stdout(&o);

    // rebuild the expected text from the fixture: each model's option lines go after its
    // parameters (before its `toml:` line); "parameters: none" stays only for models with
    // neither parameters nor options
    let mut expected = String::new();
    let (mut family, mut model) = (String::new(), String::new());
    for line in include_str!("fixtures/models_before.txt").lines() {
        if let Some(rest) = line.strip_prefix("[closures.") {
            family = rest.split(']').next().unwrap().to_string();
        } else if line.starts_with("  ") && !line.starts_with("   ") {
            model = line.trim().to_string();
        }
        let mine: Vec<&String> =
            extra.iter().filter(|(f, m, _)| *f == family && *m == model).map(|(_, _, l)| l).collect();
        if line.trim() == "parameters: none" && !mine.is_empty() {
            continue;
        }
        if line.trim_start().starts_with("toml:") {
            for l in mine {
                expected.push_str(l);
                expected.push('\n');
            }
        }
        expected.push_str(line);
        expected.push('\n');
    }
    assert_eq!(now, expected);
}

#[test]
fn string_options_are_listed_with_their_allowed_values() {
    let json: serde_json::Value = serde_json::from_str(&stdout(&saltus(&["models", "--json"]))).unwrap();
    let find = |model: &str, key: &str| {
        json.as_array()
            .unwrap()
            .iter()
            .find(|m| m["name"] == model)
            .and_then(|m| m["options"].as_array().unwrap().iter().find(|o| o["name"] == key).cloned())
            .unwrap_or_else(|| panic!("{model}: no option {key}"))
    };
    let allowed = |model: &str, key: &str| -> Vec<String> {
        find(model, key)["allowed"].as_array().unwrap().iter().map(|a| a.as_str().unwrap().to_string()).collect()
    };
    assert_eq!(allowed("mixing_length", "form"), ["prandtl", "li_sawamoto", "berzi_fraccarollo"]);
    assert_eq!(allowed("di_felice", "reynolds"), ["superficial", "interstitial"]);
    assert_eq!(allowed("frictional_collisional", "drag_dissipation"), ["linear", "quadratic"]);
    assert_eq!(allowed("k_omega", "wall"), ["smooth", "rough"]);
    assert_eq!(
        allowed("frictional_collisional", "g0.type"),
        [
            "carnahan_starling",
            "chialvo_sundaresan",
            "chialvo_sundaresan_friction",
            "chialvo_sundaresan_power",
            "torquato"
        ]
    );
    assert_eq!(find("mixing_length", "form")["default"], "li_sawamoto");
}

#[test]
fn every_allowed_value_is_accepted_by_the_scene_parser() {
    // the derive spells values from serde's renaming rules; a scene must accept each one
    saltus::ensure_registry().unwrap();
    let json: serde_json::Value = serde_json::from_str(&stdout(&saltus(&["models", "--json"]))).unwrap();
    for m in json.as_array().unwrap() {
        let family = m["family"].as_str().unwrap();
        for o in m["options"].as_array().unwrap() {
            let key = o["name"].as_str().unwrap();
            for v in o["allowed"].as_array().unwrap() {
                let v = v.as_str().unwrap();
                let value = if v == "true" || v == "false" { v.to_string() } else { format!("\"{v}\"") };
                // a dotted key sets a sub-table key; the TOML parser makes the table
                let parsed: toml::Table = format!("{key} = {value}\n").parse().unwrap();
                let entry = saltus_core::registry::models()
                    .into_iter()
                    .find(|e| e.family.key() == family && e.name == m["name"])
                    .expect("registered");
                let r = (entry.check_toml)(toml::Value::Table(parsed));
                assert!(r.is_ok(), "{family}/{} {key} = {value}: {r:?}", m["name"]);
            }
        }
    }
}
