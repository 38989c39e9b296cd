//! Registry of closure models, for listing and for checking that registrations did not
//! vanish at link time.
//!
//! typetag (de)serialises the models; this registry adds what typetag does not expose: a
//! list of every model per family with a default instance to describe it. A model that is
//! registered with typetag but not here still works in scenes, but `saltus models` does not
//! list it and the uniqueness and round-trip tests do not see it, so register both.

use crate::closure::Family;
use crate::param::Describe;

/// One registered model: family, name and a constructor of its default instance.
pub struct ModelEntry {
    /// family of the model
    pub family: Family,
    /// registered name, equal to its typetag name
    pub name: &'static str,
    /// default instance, as a describable object
    pub default: fn() -> Box<dyn Describe>,
    /// default instance serialised as a TOML table (with its `type`), for round trips
    pub default_toml: fn() -> Result<String, String>,
    /// deserialise the model's parameters (its table without `type`) as the concrete
    /// type: the key path and message of the first error, which typetag loses
    pub check_toml: fn(toml::Value) -> Result<(), (String, String)>,
}

inventory::collect!(ModelEntry);

/// Every registered model, sorted by family then name.
pub fn models() -> Vec<&'static ModelEntry> {
    let mut v: Vec<&'static ModelEntry> = inventory::iter::<ModelEntry>.into_iter().collect();
    v.sort_by(|a, b| (a.family, a.name).cmp(&(b.family, b.name)));
    v
}

/// Registered models of one family, sorted by name.
pub fn models_of(family: Family) -> Vec<&'static ModelEntry> {
    models().into_iter().filter(|m| m.family == family).collect()
}

/// Register a model: `register_model!(Family::Drag, "dallavalle", DragLaw, Dallavalle);`
/// The type must implement `Default`, `Describe` and the family trait (whose trait-object
/// type is given so that the TOML form carries the `type` tag).
#[macro_export]
macro_rules! register_model {
    ($family:expr, $name:literal, $trait_:path, $ty:ty) => {
        $crate::inventory::submit! {
            $crate::registry::ModelEntry {
                family: $family,
                name: $name,
                default: || ::std::boxed::Box::new(<$ty as ::std::default::Default>::default()),
                default_toml: || {
                    let b: ::std::boxed::Box<dyn $trait_> =
                        ::std::boxed::Box::new(<$ty as ::std::default::Default>::default());
                    $crate::scene::to_toml_table(&b)
                },
                check_toml: $crate::scene::de_concrete::<$ty>,
            }
        }
    };
}
