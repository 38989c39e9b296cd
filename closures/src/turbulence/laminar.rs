//! Laminar flow: no turbulence closure.

use saltus_core::closure::Family;
use saltus_core::{register_model, ColumnView, Describe, Needs, Turbulence};
use serde::{Deserialize, Serialize};

/// Laminar flow: no turbulent mixing.
///
/// l_m = 0, hence nu_t = l_m^2 |du/dz| = 0 and R_xz = 0.
///
/// * Source: the clear-fluid limit of Chassagne et al. 2023 eq 2.7 (nu_t = 0); used by the
///   laminar benchmarks of docs/verification.md (Couette, laminar open channel).
/// * Defaults: none (the model has no parameter).
/// * Valid range: any laminar flow; for turbulent flow choose `mixing_length`.
/// * Decision: the model `provides` no field ([`Needs::NONE`]), not an identically zero eddy
///   viscosity or Reynolds stress. A fluctuation model (`drw`, `eim`) on laminar flow is
///   meaningless, so the scene check refuses it instead of silently drawing zero
///   fluctuations. The solver still gets nu_t = 0 from [`Turbulence::eddy_viscosity`].
/// * No declared limit: l_m = 0 everywhere, so l_m / z -> kappa at the wall does not hold
///   (no turbulent mixing near the wall or anywhere else).
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(name = "laminar", source = "Chassagne et al. 2023 eq 2.7 with nu_t = 0", equation = "l_m = 0, nu_t = 0")]
pub struct Laminar {}

#[typetag::serde(name = "laminar")]
impl Turbulence for Laminar {
    fn provides(&self) -> Needs {
        Needs::NONE
    }

    fn mixing_length(&self, _col: &ColumnView<'_>, out: &mut [f64]) {
        out.fill(0.0);
    }

    #[inline]
    fn eddy_viscosity_point(&self, _l_m: f64, _dudz: f64) -> f64 {
        0.0
    }
}

register_model!(Family::Turbulence, "laminar", Turbulence, Laminar);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use saltus_core::Field;

    proptest! {
        #[test]
        fn zero_mixing_length_and_eddy_viscosity(
            dudz in proptest::collection::vec(-1e3f64..1e3, 1..32),
        ) {
            let n = dudz.len();
            let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * 0.01).collect();
            let dz = vec![0.01; n];
            let phi = vec![0.1; n];
            let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: 1e-3, nu_f: 1e-6, transported: &[] };
            let lam = Laminar::default();
            let mut out = vec![1.0; n];
            lam.mixing_length(&col, &mut out);
            prop_assert!(out.iter().all(|&l| l == 0.0));
            out.fill(1.0);
            lam.eddy_viscosity(&col, &mut out);
            prop_assert!(out.iter().all(|&nu| nu == 0.0));
        }
    }

    #[test]
    fn provides_nothing_so_fluctuations_are_refused() {
        let lam = Laminar::default();
        assert!(lam.provides().is_empty());
        let drw_needs = Needs::of(&[Field::ReynoldsStress]);
        assert_eq!(drw_needs.missing(lam.provides()).collect::<Vec<_>>(), vec![Field::ReynoldsStress]);
        assert!(lam.validate().is_ok());
        assert!(lam.transported().is_empty());
    }

    #[test]
    fn refuses_unknown_keys() {
        let r: Result<Laminar, _> = toml::from_str("kappa = 0.41");
        assert!(r.is_err());
    }
}
