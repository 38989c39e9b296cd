//! Turbulence closures of the fluid column (family `turbulence`): laminar flow and
//! algebraic mixing-length models, and the two-phase low-Reynolds k-omega transport model.

pub mod k_omega;
pub mod laminar;
pub mod mixing_length;
pub mod parabolic;

pub use k_omega::{KOmega, KOmegaWall};
pub use laminar::Laminar;
pub use mixing_length::{MixingLength, MixingLengthForm};
pub use parabolic::Parabolic;

#[cfg(test)]
mod tests {
    #[test]
    fn every_turbulence_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::Turbulence>(saltus_core::closure::Family::Turbulence);
    }
}
