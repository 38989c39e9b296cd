//! Granular stress closures (family `granular`): local rheologies `mu_i` and `mu_k`, and the
//! frictional-collisional kinetic theory `frictional_collisional` with its parts in
//! [`kinetic`].

pub mod frictional_collisional;
pub mod kinetic;
pub mod mu_i;
pub mod mu_k;

pub use frictional_collisional::{FrictionalCollisional, StaticFriction};
pub use mu_i::MuI;
pub use mu_k::MuK;

#[cfg(test)]
mod tests {
    #[test]
    fn every_granular_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::GranularStress>(saltus_core::closure::Family::Granular);
    }
}
