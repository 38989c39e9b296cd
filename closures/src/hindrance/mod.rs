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

    #[test]
    fn every_model_batch_equals_scalar() {
        use saltus_core::closure::Family;
        let (phi, re) = crate::testing::sample_inputs();
        for m in crate::testing::registered::<dyn saltus_core::Hindrance>(Family::Hindrance) {
            let mut out = vec![0.0; re.len()];
            m.factor_batch(&phi, &re, &mut out);
            for ((o, p), r) in out.iter().zip(&phi).zip(&re) {
                assert_eq!(o.to_bits(), m.factor(*p, *r).to_bits(), "{} at phi {p}, Re {r}", m.name());
            }
        }
    }
}
