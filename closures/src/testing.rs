//! Helpers shared by the closures' unit tests.

use approx::assert_relative_eq;
use saltus_core::closure::Family;
use saltus_core::{registry, LocalRheology, LocalState};

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

/// A local rheology seen only through its four required methods, so that every other
/// method of [`LocalRheology`] is the trait's generic default (the bisections).
struct Generic<'a>(&'a dyn LocalRheology);

impl LocalRheology for Generic<'_> {
    fn control_name(&self) -> &'static str {
        self.0.control_name()
    }
    fn control_number(&self, s: &LocalState) -> f64 {
        self.0.control_number(s)
    }
    fn friction(&self, x: f64) -> f64 {
        self.0.friction(x)
    }
    fn packing(&self, x: f64) -> f64 {
        self.0.packing(x)
    }
}

/// The closed-form inverses of local rheology `m` agree with the trait's generic
/// bisection at each volume fraction of `phis` (below the jammed packing) and invert
/// their laws: packing(control_of_packing(phi)) = phi and, at the sheared state `s` (its
/// pressure ignored), control_number(pressure_at(s, x)) = x. At and above the jammed
/// packing the control number is 0, and an unsheared state carries no pressure.
pub fn assert_inverses_match_bisection(m: &dyn LocalRheology, s: &LocalState, phis: &[f64]) {
    let g = Generic(m);
    for &phi in phis {
        let x = m.control_of_packing(phi);
        assert_relative_eq!(x, g.control_of_packing(phi), max_relative = 1e-10);
        assert_relative_eq!(m.packing(x), phi, max_relative = 1e-12);
        let p = m.pressure_at(s, x);
        assert_relative_eq!(p, g.pressure_at(s, x), max_relative = 1e-10);
        assert_relative_eq!(m.control_number(&LocalState { pressure: p, ..*s }), x, max_relative = 1e-12);
    }
    let jammed = m.packing(0.0);
    assert_eq!(m.control_of_packing(jammed), 0.0);
    assert_eq!(m.control_of_packing(jammed + 0.05), 0.0);
    assert_eq!(m.pressure_at(&LocalState { shear_rate: 0.0, ..*s }, 0.1), 0.0);
}

/// [`LocalRheology::eval_batch`] of `m` over `x` gives, bit for bit, its scalar friction
/// and packing.
pub fn assert_batch_equals_scalar(m: &dyn LocalRheology, x: &[f64]) {
    let (mut mu, mut phi) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    m.eval_batch(x, &mut mu, &mut phi);
    for i in 0..x.len() {
        assert_eq!(mu[i].to_bits(), m.friction(x[i]).to_bits(), "friction at {}", x[i]);
        assert_eq!(phi[i].to_bits(), m.packing(x[i]).to_bits(), "packing at {}", x[i]);
    }
}
