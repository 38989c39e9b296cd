//! Single-particle drag laws C_D(Re_p) (family `drag`).

pub mod dallavalle;
pub mod haider_levenspiel;
pub mod schiller_naumann;
pub mod stokes;

pub use dallavalle::Dallavalle;
pub use haider_levenspiel::HaiderLevenspiel;
pub use schiller_naumann::SchillerNaumann;
pub use stokes::Stokes;

#[cfg(test)]
mod tests {
    #[test]
    fn every_drag_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::DragLaw>(saltus_core::closure::Family::Drag);
    }
}
