//! Hindrance (crowding) factors of the drag force f(phi, Re_p) (family `hindrance`).

pub mod di_felice;
pub mod none;
pub mod richardson_zaki;

pub use di_felice::{DiFelice, ReynoldsConvention};
pub use none::NoHindrance;
pub use richardson_zaki::RichardsonZaki;

#[cfg(test)]
mod tests {
    #[test]
    fn every_hindrance_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::Hindrance>(saltus_core::closure::Family::Hindrance);
    }
}
