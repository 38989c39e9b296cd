//! The models of closures registered at run time ([`saltus_core::runtime`]): adapters
//! that implement the family traits by calling the registered functions on whole slices,
//! so that a solver's batch call (a column, a chunk of particles) is one call of the
//! function. [`RuntimeClosure`] holds the drag, hindrance, viscosity and wall-friction
//! laws and is the caller the other adapters share: [`local`] (granular local rheology),
//! [`kinetic`] (kinetic-theory coefficient set), [`mixing_length`] (algebraic turbulence),
//! [`fluctuation`] (particle draws and mean-field diffusivity).
//!
//! The law itself is the user's; what the adapter adds, documented with the trait it
//! fills:
//! * C_D Re_p ([`DragLaw::cd_re`]) is the law's own `cd_re` output when it gives one
//!   ([`saltus_core::runtime::optional_outputs`]; its C_D may then be +inf at Re_p = 0,
//!   [`saltus_core::runtime::accepts`]), else C_D(r) r at r = max(Re_p, [`RE_MIN`]),
//!   finite at Re_p = 0 (the DEM evaluates C_D at the same clamped Re_p,
//!   `solvers/src/lagrangian/drag.rs`): for a law tending to a / Re_p the error at
//!   Re_p < [`RE_MIN`] is then C_D^inf [`RE_MIN`] relative to a.
//! * C_D^inf ([`DragLaw::cd_inf`], the quadratic drag dissipation of Chassagne et al. 2023
//!   eq 3.13) is C_D at Re_p = [`RE_INF`], evaluated once when the model is built (the
//!   call that also tells whether the law gives `cd_re`): exact for C_D = c + a / Re_p,
//!   which rounds to c there.
//! * A function that fails (raises, returns a wrong shape or a non-finite value) fills its
//!   outputs with NaN, keeps the first message ([`Describe::failure`]) and is not called
//!   again: the run driver ends the run with that message.

use std::fmt;
use std::sync::{Arc, OnceLock};

use saltus_core::closure::Family;
use saltus_core::runtime::{BatchFunction, Built, RuntimeModel, Shape};
use saltus_core::{Describe, DragLaw, DragReynolds, EffectiveViscosity, Hindrance, Limit, Param, WallFriction};
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

pub mod fluctuation;
pub mod kinetic;
pub mod local;
pub mod mixing_length;

/// Smallest Re_p at which C_D Re_p of a run-time drag law is evaluated (the DEM's clamp
/// of Re*).
pub const RE_MIN: f64 = 1e-12;

/// Re_p at which C_D of a run-time drag law is taken as C_D^inf.
pub const RE_INF: f64 = 1e150;

/// A closure registered at run time with its parameter values.
pub struct RuntimeClosure {
    model: Arc<RuntimeModel>,
    values: Vec<f64>,
    cd_inf: f64,
    /// a drag law that returns `cd_re`
    gives_cd_re: bool,
    failure: OnceLock<String>,
}

impl fmt::Debug for RuntimeClosure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RuntimeClosure").field("model", &self.model.name).field("values", &self.values).finish()
    }
}

/// The [`saltus_core::runtime::RuntimeModel::build`] of every run-time closure: the
/// adapter at `values`, as the trait object of the model's family. A drag law is
/// evaluated once here for its C_D^inf, which must be finite and >= 0.
pub fn build(model: &Arc<RuntimeModel>, values: Vec<f64>) -> Result<Built, String> {
    let c = RuntimeClosure::new(model, values);
    Ok(match (model.family, &model.shape) {
        (Family::Granular, Shape::Local { .. }) => Built::Granular(Box::new(local::RuntimeLocal::new(c))),
        (Family::Granular, Shape::Kinetic { .. }) => Built::Granular(Box::new(kinetic::RuntimeKinetic::new(c)?)),
        (Family::Turbulence, Shape::MixingLength) => {
            Built::Turbulence(Box::new(mixing_length::RuntimeMixingLength::new(c)))
        }
        (Family::Fluctuation, Shape::Fluctuation { .. }) => {
            Built::Fluctuation(Box::new(fluctuation::RuntimeFluctuation::new(c)))
        }
        (_, Shape::Plain) => plain(c, model)?,
        (other, _) => return Err(saltus_core::runtime::refused(other)),
    })
}

/// The law of a one-function family.
fn plain(mut c: RuntimeClosure, model: &Arc<RuntimeModel>) -> Result<Built, String> {
    Ok(match model.family {
        Family::Drag => {
            // one call: C_D^inf, and whether the law gives C_D Re_p
            let (mut cd, mut cd_re) = ([0.0], [0.0]);
            c.gives_cd_re = c.call(&[&[RE_INF]], &mut [&mut cd, &mut cd_re]) == 2;
            let cd_inf = cd[0];
            if let Some(f) = c.failure.get() {
                return Err(f.clone());
            }
            if !(cd_inf.is_finite() && cd_inf >= 0.0) {
                return Err(format!(
                    "closure `{}`: C_D at Re_p = 1e150 is {cd_inf}; the drag dissipation needs C_D^inf, finite and >= 0",
                    model.name
                ));
            }
            c.cd_inf = cd_inf;
            Built::Drag(Box::new(c))
        }
        Family::Hindrance => Built::Hindrance(Box::new(c)),
        Family::Viscosity => Built::Viscosity(Box::new(c)),
        Family::WallFriction => Built::WallFriction(Box::new(c)),
        other => return Err(saltus_core::runtime::refused(other)),
    })
}

impl RuntimeClosure {
    fn new(model: &Arc<RuntimeModel>, values: Vec<f64>) -> Self {
        RuntimeClosure { model: Arc::clone(model), values, cd_inf: 0.0, gives_cd_re: false, failure: OnceLock::new() }
    }

    /// The value of parameter `name` (NaN if the model has none: [`register`] of core
    /// refuses the shapes that need a missing one).
    ///
    /// [`register`]: saltus_core::runtime::register
    fn param(&self, name: &str) -> f64 {
        self.model.params.iter().position(|p| p.name == name).map_or(f64::NAN, |i| self.values[i])
    }

    /// The function on `inputs` into `outputs`; how many outputs it wrote. On failure
    /// NaN everywhere and the first message kept.
    fn call(&self, inputs: &[&[f64]], outputs: &mut [&mut [f64]]) -> usize {
        self.call_face(&*self.model.function, &[], inputs, outputs)
    }

    /// Face `function` with the parameters followed by `context` (the face's scalar
    /// keywords), as [`RuntimeClosure::call`].
    fn call_face(
        &self,
        function: &dyn BatchFunction,
        context: &[f64],
        inputs: &[&[f64]],
        outputs: &mut [&mut [f64]],
    ) -> usize {
        if self.failure.get().is_none() {
            // one small vector per batch when the face has scalar keywords
            let params = if context.is_empty() {
                std::borrow::Cow::Borrowed(&self.values[..])
            } else {
                std::borrow::Cow::Owned([&self.values[..], context].concat())
            };
            match function.evaluate(&params, inputs, outputs) {
                Ok(n) => return n,
                Err(m) => {
                    let _ = self.failure.set(format!("{} closure `{}`: {m}", self.model.family, self.model.name));
                }
            }
        }
        for o in outputs.iter_mut() {
            o.fill(f64::NAN);
        }
        outputs.len()
    }

    /// One output at one point.
    fn scalar(&self, inputs: &[f64]) -> f64 {
        let columns: Vec<&[f64]> = inputs.iter().map(std::slice::from_ref).collect();
        let mut out = [0.0];
        self.call(&columns, &mut [&mut out[..]]);
        out[0]
    }
}

impl Serialize for RuntimeClosure {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.values.len()))?;
        for (p, v) in self.model.params.iter().zip(&self.values) {
            map.serialize_entry(&p.name, v)?;
        }
        map.end()
    }
}

impl Describe for RuntimeClosure {
    fn name(&self) -> &'static str {
        self.model.name
    }
    fn source(&self) -> &'static str {
        self.model.source
    }
    fn equation(&self) -> &'static str {
        self.model.equation
    }
    fn params(&self) -> Vec<Param> {
        self.model.params_at(&self.values)
    }
    fn limits(&self) -> Vec<Limit> {
        self.model.limits.iter().map(|l| l.at(&self.values)).collect()
    }
    fn failure(&self) -> Option<String> {
        self.failure.get().cloned()
    }
}

/// [`Describe`], [`Serialize`] and [`fmt::Debug`] of an adapter that holds its
/// [`RuntimeClosure`] as `c`: those of the closure.
macro_rules! as_runtime_closure {
    ($t:ty) => {
        impl std::fmt::Debug for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.c.fmt(f)
            }
        }
        impl serde::Serialize for $t {
            fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                self.c.serialize(serializer)
            }
        }
        impl saltus_core::Describe for $t {
            fn name(&self) -> &'static str {
                self.c.name()
            }
            fn source(&self) -> &'static str {
                self.c.source()
            }
            fn equation(&self) -> &'static str {
                self.c.equation()
            }
            fn params(&self) -> Vec<saltus_core::Param> {
                self.c.params()
            }
            fn limits(&self) -> Vec<saltus_core::Limit> {
                self.c.limits()
            }
            fn failure(&self) -> Option<String> {
                self.c.failure()
            }
        }
    };
}
use as_runtime_closure;

// The family traits are implemented by hand, not with `#[typetag::serde]`: typetag's
// registrations are compiled in, and this one type stands for every run-time name. The two
// hidden methods are what the attribute would write; `typetag_name` gives the registered
// name, so a resolved scene writes `type = "<name>"` and reads back through the run-time
// registry.
impl DragLaw for RuntimeClosure {
    fn typetag_name(&self) -> &'static str {
        self.model.name
    }
    fn typetag_deserialize(&self) {}

    fn cd(&self, re_p: f64) -> f64 {
        self.scalar(&[re_p])
    }
    fn cd_re(&self, re_p: f64) -> f64 {
        let mut out = [0.0];
        self.cd_re_batch(&[re_p], &mut out);
        out[0]
    }
    fn cd_inf(&self) -> f64 {
        self.cd_inf
    }
    fn cd_batch(&self, re_p: &[f64], out: &mut [f64]) {
        self.call(&[re_p], &mut [out]);
    }
    fn cd_re_batch(&self, re_p: &[f64], out: &mut [f64]) {
        // one or two allocations per batch, beside the function's own arrays
        let mut cd = vec![0.0; re_p.len()];
        if self.gives_cd_re {
            // at Re_p itself, 0 included: its C_D may be +inf there
            self.call(&[re_p], &mut [&mut cd, &mut *out]);
            return;
        }
        let r: Vec<f64> = re_p.iter().map(|&x| x.max(RE_MIN)).collect();
        self.call(&[&r], &mut [&mut cd]);
        for ((o, c), x) in out.iter_mut().zip(&cd).zip(&r) {
            *o = c * x;
        }
    }
}

impl Hindrance for RuntimeClosure {
    fn typetag_name(&self) -> &'static str {
        self.model.name
    }
    fn typetag_deserialize(&self) {}

    fn factor(&self, phi: f64, re_p: f64) -> f64 {
        self.scalar(&[phi, re_p])
    }
    fn reynolds_convention(&self) -> DragReynolds {
        self.model.convention
    }
    fn depends_on_reynolds(&self) -> bool {
        self.model.depends_on_reynolds
    }
    fn factor_batch(&self, phi: &[f64], re_p: &[f64], out: &mut [f64]) {
        self.call(&[phi, re_p], &mut [out]);
    }
}

impl EffectiveViscosity for RuntimeClosure {
    fn typetag_name(&self) -> &'static str {
        self.model.name
    }
    fn typetag_deserialize(&self) {}

    fn ratio(&self, phi: f64) -> f64 {
        self.scalar(&[phi])
    }
    fn ratio_batch(&self, phi: &[f64], out: &mut [f64]) {
        self.call(&[phi], &mut [out]);
    }
}

/// The function's output is the Poiseuille number f Re (`f_re`), finite where the flow
/// stops, from which the trait's default gives f = f Re / Re.
impl WallFriction for RuntimeClosure {
    fn typetag_name(&self) -> &'static str {
        self.model.name
    }
    fn typetag_deserialize(&self) {}

    fn poiseuille_number(&self, re: f64) -> f64 {
        self.scalar(&[re])
    }
    fn poiseuille_batch(&self, re: &mut [f64]) {
        // in place: the inputs copied once per batch
        let input = re.to_vec();
        self.call(&[&input], &mut [re]);
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod face_tests;
