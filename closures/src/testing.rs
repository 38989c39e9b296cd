//! Helpers shared by the closures' unit tests.

use saltus_core::closure::Family;
use saltus_core::registry;

/// Every registered model of `family` must round-trip through TOML: serialise the default,
/// parse it back through the scene machinery, serialise again, and get the same text.
pub fn assert_round_trip<T>(family: Family)
where
    T: ?Sized + saltus_core::Describe + saltus_core::runtime::FromRuntime,
    Box<T>: serde::de::DeserializeOwned + serde::Serialize,
{
    let models = registry::models_of(family);
    assert!(!models.is_empty(), "no {family} model registered");
    for m in models {
        let text = (m.default_toml)().unwrap_or_else(|e| panic!("{}: {e}", m.name));
        let value: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}\n{text}", m.name));
        let back: Box<T> = saltus_core::scene::closure_from_value(
            toml::Value::Table(value),
            family,
            std::path::Path::new("round_trip.toml"),
            "closures.x",
        )
        .unwrap_or_else(|e| panic!("{}: {e}\n{text}", m.name));
        assert_eq!(back.name(), m.name);
        let again = saltus_core::scene::to_toml_table(&back).unwrap();
        assert_eq!(again, text, "{} does not round-trip", m.name);
        assert!(back.validate().is_ok(), "default of {} is invalid", m.name);
    }
}

/// Every registered model of `family`, built from its default TOML through the scene
/// machinery (so models added later are covered without writing a test).
pub fn registered<T>(family: Family) -> Vec<Box<T>>
where
    T: ?Sized + saltus_core::Describe + saltus_core::runtime::FromRuntime,
    Box<T>: serde::de::DeserializeOwned,
{
    registry::models_of(family)
        .into_iter()
        .map(|m| {
            let text = (m.default_toml)().unwrap_or_else(|e| panic!("{}: {e}", m.name));
            let table: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}", m.name));
            saltus_core::scene::closure_from_value(
                toml::Value::Table(table),
                family,
                std::path::Path::new("batch.toml"),
                "closures.x",
            )
            .unwrap_or_else(|e| panic!("{}: {e}", m.name))
        })
        .collect()
}

/// Volume fractions and Reynolds numbers covering the valid ranges, bed to dilute.
pub fn sample_inputs() -> (Vec<f64>, Vec<f64>) {
    let phi: Vec<f64> = (0..97).map(|i| i as f64 * 0.0065).collect();
    let re: Vec<f64> = (0..97).map(|i| 10f64.powf(-4.0 + i as f64 * 0.09)).collect();
    (phi, re)
}
