//! What closures need from the flow state, and what other closures provide.
//!
//! The scene is checked once before a run: every [`Field`] a closure needs must be
//! provided by the turbulence closure, the granular closure or the solver itself.

use std::fmt;

/// A state field that a closure may need.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Field {
    /// eddy viscosity nu_t (m^2/s)
    EddyViscosity,
    /// turbulent kinetic energy k (m^2/s^2)
    Tke,
    /// specific dissipation rate omega (1/s)
    Omega,
    /// Reynolds shear stress R_xz / (rho_f (1 - phi)) (m^2/s^2)
    ReynoldsStress,
    /// granular temperature T (m^2/s^2)
    GranularTemperature,
}

impl Field {
    /// Every field, in display order.
    pub const ALL: [Field; 5] =
        [Field::EddyViscosity, Field::Tke, Field::Omega, Field::ReynoldsStress, Field::GranularTemperature];

    /// Short name used in messages and manifests.
    pub fn name(self) -> &'static str {
        match self {
            Field::EddyViscosity => "eddy viscosity (nu_t)",
            Field::Tke => "turbulent kinetic energy (k)",
            Field::Omega => "specific dissipation rate (omega)",
            Field::ReynoldsStress => "Reynolds shear stress (R_xz)",
            Field::GranularTemperature => "granular temperature (T)",
        }
    }

    fn bit(self) -> u8 {
        1 << (self as u8)
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A small set of [`Field`]s.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Needs(u8);

impl Needs {
    /// The empty set.
    pub const NONE: Needs = Needs(0);

    /// Set of the given fields.
    pub fn of(fields: &[Field]) -> Self {
        Needs(fields.iter().fold(0, |acc, f| acc | f.bit()))
    }

    /// Whether `f` is in the set.
    pub fn contains(self, f: Field) -> bool {
        self.0 & f.bit() != 0
    }

    /// Union of two sets.
    pub fn union(self, other: Needs) -> Needs {
        Needs(self.0 | other.0)
    }

    /// Fields of `self` not in `provided`.
    pub fn missing(self, provided: Needs) -> impl Iterator<Item = Field> {
        Field::ALL.into_iter().filter(move |f| self.contains(*f) && !provided.contains(*f))
    }

    /// Iterate over the fields in the set.
    pub fn iter(self) -> impl Iterator<Item = Field> {
        Field::ALL.into_iter().filter(move |f| self.contains(*f))
    }

    /// Whether the set is empty.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_is_set_difference() {
        let need = Needs::of(&[Field::Tke, Field::Omega]);
        let have = Needs::of(&[Field::Tke, Field::EddyViscosity]);
        let m: Vec<_> = need.missing(have).collect();
        assert_eq!(m, vec![Field::Omega]);
        assert!(Needs::NONE.missing(have).next().is_none());
    }
}
