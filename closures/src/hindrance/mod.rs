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

    /// The declared convention is what the model does: Re* = c(phi) Re_p with c of the
    /// convention, a Reynolds-free factor is the same at every Re_p, and a Reynolds-
    /// dependent one sees Re_p only through Re* (the Di Felice exponent of Re*).
    #[test]
    fn every_model_follows_its_declared_convention() {
        use saltus_core::closure::Family;
        use saltus_core::{DragReynolds, Hindrance};
        let (phi, re) = crate::testing::sample_inputs();
        let mut models = crate::testing::registered::<dyn Hindrance>(Family::Hindrance);
        models.push(Box::new(super::DiFelice { reynolds: super::ReynoldsConvention::Interstitial }));
        for m in &models {
            let c = m.reynolds_convention();
            for (&p, &r) in phi.iter().zip(&re) {
                assert_eq!(m.drag_reynolds(p, r), c.ratio(p) * r, "{}", m.name());
                assert!(c.ratio(p) > 0.0 && c.ratio(p) <= 1.0);
                if !m.depends_on_reynolds() {
                    for r2 in [0.0, 1e-3, 1.0, 1e3, 1e5] {
                        assert_eq!(m.factor(p, r).to_bits(), m.factor(p, r2).to_bits(), "{} at phi {p}", m.name());
                    }
                }
            }
        }
        for conv in [super::ReynoldsConvention::Superficial, super::ReynoldsConvention::Interstitial] {
            let m = super::DiFelice { reynolds: conv };
            let expected = match conv {
                super::ReynoldsConvention::Superficial => DragReynolds::Superficial,
                super::ReynoldsConvention::Interstitial => DragReynolds::Interstitial,
            };
            assert_eq!(m.reynolds_convention(), expected);
            assert!(m.depends_on_reynolds());
            for (&p, &r) in phi.iter().zip(&re) {
                let n = super::DiFelice::exponent(expected.of(p, r));
                assert_eq!(m.factor(p, r).to_bits(), (1.0 - p).powf(2.0 - n).to_bits());
            }
        }
    }

    proptest::proptest! {
        /// A Reynolds-free model's factor does not change with Re_p anywhere.
        #[test]
        fn reynolds_free_models_do_not_see_re(phi in 0f64..0.9, re_a in 0f64..1e5, re_b in 0f64..1e5) {
            use saltus_core::closure::Family;
            for m in crate::testing::registered::<dyn saltus_core::Hindrance>(Family::Hindrance) {
                if !m.depends_on_reynolds() {
                    proptest::prop_assert_eq!(m.factor(phi, re_a).to_bits(), m.factor(phi, re_b).to_bits());
                }
            }
        }
    }
}
