//! Single-particle drag laws C_D(Re_p) (family `drag`).

pub mod dallavalle;

pub use dallavalle::Dallavalle;

#[cfg(test)]
mod tests {
    #[test]
    fn every_drag_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::DragLaw>(saltus_core::closure::Family::Drag);
    }
}
