//! Fluid effective viscosity ratios nu_eff/nu_f(phi) (family `viscosity`).

pub mod batchelor_green;
pub mod clear_fluid;
pub mod einstein;
pub mod fry2024;
pub mod gibilaro;
pub mod krieger_dougherty;

pub use batchelor_green::BatchelorGreen;
pub use clear_fluid::ClearFluid;
pub use einstein::Einstein;
pub use fry2024::Fry2024;
pub use gibilaro::Gibilaro;
pub use krieger_dougherty::KriegerDougherty;

#[cfg(test)]
mod tests {
    #[test]
    fn every_viscosity_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::EffectiveViscosity>(
            saltus_core::closure::Family::Viscosity,
        );
    }

    #[test]
    fn every_model_batch_equals_scalar() {
        use saltus_core::closure::Family;
        let (phi, _) = crate::testing::sample_inputs();
        for m in crate::testing::registered::<dyn saltus_core::EffectiveViscosity>(Family::Viscosity) {
            let mut out = vec![0.0; phi.len()];
            m.ratio_batch(&phi, &mut out);
            for (o, p) in out.iter().zip(&phi) {
                assert_eq!(o.to_bits(), m.ratio(*p).to_bits(), "{} at phi {p}", m.name());
            }
        }
    }
}
