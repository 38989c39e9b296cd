//! No velocity fluctuation.

use saltus_core::closure::Family;
use saltus_core::rng::Rng;
use saltus_core::{
    register_model, Describe, FlowScales, Fluctuation, FluctuationDraw, Limit, Needs, ParticleSlip, TurbulencePoint,
};
use serde::{Deserialize, Serialize};

/// No fluid velocity fluctuation: particles see the mean fluid velocity only.
///
/// u' = 0 (held forever), D = 0.
///
/// * Source: the mean-field limit of Maurin et al. 2015 (without their eqs 15-16) and of
///   Chassagne et al. 2023 without the drift velocity of eqs 4.3-4.4.
/// * Defaults: none (the model has no parameter).
/// * Valid range: any flow, laminar included; it needs no turbulence field.
/// * Decision: [`Fluctuation::is_active`] is false so that the solver pays for no random
///   number and no drift velocity; `draw` consumes no random number.
/// * Declared limit: D >= 0 (D = 0).
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "none",
    source = "Maurin et al. 2015 without eqs 15-16; Chassagne et al. 2023 without eqs 4.3-4.4",
    equation = "u' = 0, D = 0",
    limits = [Limit::NonNegative]
)]
pub struct NoFluctuation {}

#[typetag::serde(name = "none")]
impl Fluctuation for NoFluctuation {
    fn needs(&self) -> Needs {
        Needs::NONE
    }

    fn is_active(&self) -> bool {
        false
    }

    fn draw(&self, _t: &TurbulencePoint, _p: &ParticleSlip, _s: &FlowScales, _rng: &mut Rng) -> FluctuationDraw {
        FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY }
    }

    fn diffusivity(&self, _t: &TurbulencePoint, _s: &FlowScales) -> f64 {
        0.0
    }
}

register_model!(Family::Fluctuation, "none", Fluctuation, NoFluctuation);

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngCore;
    use saltus_core::rng::stream;

    #[test]
    fn draws_nothing_forever_and_consumes_no_random_number() {
        let m = NoFluctuation::default();
        let tp = TurbulencePoint { k: 1.0, omega: 10.0, nu_t: 0.1, reynolds_stress: 0.01 };
        let s = FlowScales { depth: 0.1, bulk_velocity: 1.0 };
        let p = ParticleSlip { slip: 0.1, response_time: 0.01 };
        let mut a = stream(1, 0);
        let d = m.draw(&tp, &p, &s, &mut a);
        assert_eq!(d, FluctuationDraw { u: [0.0; 3], duration: f64::INFINITY });
        assert_eq!(a.next_u64(), stream(1, 0).next_u64());
        assert_eq!(m.diffusivity(&tp, &s), 0.0);
        let mut out = [1.0; 3];
        m.diffusivity_batch(&[tp; 3], &s, &mut out);
        assert_eq!(out, [0.0; 3]);
        assert!(!m.is_active());
        assert!(m.needs().is_empty());
        assert!(m.validate().is_ok());
    }
}
