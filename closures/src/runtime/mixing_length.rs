//! An algebraic turbulence closure registered at run time: the mixing length l_m over the
//! cells of one column, one call per column evaluation, and the Prandtl eddy viscosity
//! nu_t = l_m^2 |du/dz| of it (Chassagne et al. 2023 eq 2.8a, the trait's default).

use saltus_core::{ColumnView, Field, Needs, Turbulence};

use super::{as_runtime_closure, RuntimeClosure};

/// A mixing-length closure whose length is a registered function.
pub struct RuntimeMixingLength {
    c: RuntimeClosure,
}

as_runtime_closure!(RuntimeMixingLength);

impl RuntimeMixingLength {
    pub(super) fn new(c: RuntimeClosure) -> Self {
        RuntimeMixingLength { c }
    }
}

// typetag's two hidden methods by hand, as for the one-function families (runtime.rs)
impl Turbulence for RuntimeMixingLength {
    fn typetag_name(&self) -> &'static str {
        self.c.model.name
    }
    fn typetag_deserialize(&self) {}

    // as the built-in mixing length: nu_t and the Reynolds stress nu_t du/dz
    fn provides(&self) -> Needs {
        Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress])
    }

    fn mixing_length(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        self.c.call_face(
            &*self.c.model.function,
            &[col.diameter, col.nu_f],
            &[col.z, col.dz, col.phi, col.dudz],
            &mut [out],
        );
    }
}
