//! The closure registry as a binary sees it: non-empty (registrations did not vanish at
//! link time), unique names per family, every model round-trips through TOML and its
//! default is valid, and every model has a section in docs/closures/.

use std::collections::HashSet;
use std::path::Path;

use saltus_core::closure::Family;
use saltus_core::registry;

#[test]
fn registry_is_not_empty_in_a_binary_that_links_the_closures() {
    let n = saltus::ensure_registry().expect("registrations present");
    assert!(n >= 19, "only {n} models registered");
    for f in Family::ALL {
        assert!(!registry::models_of(f).is_empty(), "family {f} has no model");
    }
}

#[test]
fn model_names_are_unique_within_each_family() {
    saltus_closures::link();
    let mut seen = HashSet::new();
    for m in registry::models() {
        assert!(seen.insert((m.family, m.name)), "duplicate model `{}` in family {}", m.name, m.family);
        assert_eq!((m.default)().name(), m.name, "registered name differs from Describe::name");
    }
}

fn round_trip<T>(family: Family)
where
    T: ?Sized + saltus_core::Describe + saltus_core::runtime::FromRuntime,
    Box<T>: serde::de::DeserializeOwned + serde::Serialize,
{
    for m in registry::models_of(family) {
        let text = (m.default_toml)().unwrap_or_else(|e| panic!("{}: {e}", m.name));
        let table: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}", m.name));
        let model: Box<T> =
            saltus_core::scene::closure_from_value(toml::Value::Table(table), family, Path::new("rt.toml"), "x")
                .unwrap_or_else(|e| panic!("{}: {e}", m.name));
        assert_eq!(saltus_core::scene::to_toml_table(&model).unwrap(), text, "{} does not round-trip", m.name);
        model.validate().unwrap_or_else(|e| panic!("default of {} invalid: {e}", m.name));
    }
}

#[test]
fn every_registered_model_round_trips_through_toml() {
    saltus_closures::link();
    round_trip::<dyn saltus_core::DragLaw>(Family::Drag);
    round_trip::<dyn saltus_core::Hindrance>(Family::Hindrance);
    round_trip::<dyn saltus_core::EffectiveViscosity>(Family::Viscosity);
    round_trip::<dyn saltus_core::GranularStress>(Family::Granular);
    round_trip::<dyn saltus_core::Turbulence>(Family::Turbulence);
    round_trip::<dyn saltus_core::Fluctuation>(Family::Fluctuation);
}

#[test]
fn every_registered_model_has_a_documentation_section_with_its_source() {
    saltus_closures::link();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/closures");
    for m in registry::models() {
        let page = root.join(format!("{}.md", m.family.key()));
        let text = std::fs::read_to_string(&page).unwrap_or_else(|e| panic!("{}: {e}", page.display()));
        let heading = format!("### {}", m.name);
        let start = text
            .lines()
            .position(|l| l.trim() == heading)
            .unwrap_or_else(|| panic!("{} lacks a section `{heading}`", page.display()));
        let section: String =
            text.lines().skip(start + 1).take_while(|l| !l.starts_with("### ")).collect::<Vec<_>>().join("\n");
        let lower = section.to_lowercase();
        for word in ["source", "default", "range"] {
            assert!(lower.contains(word), "{}: section `{}` does not mention its {word}", page.display(), m.name);
        }
    }
}
