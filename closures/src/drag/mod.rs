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

    #[test]
    fn every_model_batch_equals_scalar() {
        use saltus_core::closure::Family;
        let (_, re) = crate::testing::sample_inputs();
        for m in crate::testing::registered::<dyn saltus_core::DragLaw>(Family::Drag) {
            let mut out = vec![0.0; re.len()];
            m.cd_batch(&re, &mut out);
            for (o, r) in out.iter().zip(&re) {
                assert_eq!(o.to_bits(), m.cd(*r).to_bits(), "{} at Re {r}", m.name());
            }
        }
    }
}
