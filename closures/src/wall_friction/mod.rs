//! Friction factors of smooth side walls on the fluid of a narrow channel (family
//! `wall_friction`).

pub mod graf_altinakar;
pub mod none;

pub use graf_altinakar::GrafAltinakar;
pub use none::NoWallFriction;

#[cfg(test)]
mod tests {
    #[test]
    fn every_wall_friction_model_round_trips() {
        crate::testing::assert_round_trip::<dyn saltus_core::WallFriction>(saltus_core::closure::Family::WallFriction);
    }

    #[test]
    fn every_model_batch_equals_scalar() {
        use saltus_core::closure::Family;
        let re: Vec<f64> = (0..40).map(|i| 10f64.powf(-2.0 + 0.25 * i as f64)).collect();
        for m in crate::testing::registered::<dyn saltus_core::WallFriction>(Family::WallFriction) {
            let mut out = re.clone();
            m.poiseuille_batch(&mut out);
            for (o, r) in out.iter().zip(&re) {
                assert_eq!(o.to_bits(), m.poiseuille_number(*r).to_bits(), "{} at Re {r}", m.name());
            }
        }
    }
}
