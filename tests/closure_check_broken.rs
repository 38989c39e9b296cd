//! Deliberately broken models, registered in this test binary only: `saltus closure check`
//! must fail them with a report naming the check and a shrunk input.

use saltus_core::closure::Family;
use saltus_core::{register_model, Describe, DragLaw, DragReynolds, Hindrance, Limit};
use serde::{Deserialize, Serialize};

/// A drag law that is NaN below Re_p = 1e-3 (a sqrt of a negative number).
#[derive(Clone, Debug, Serialize, Deserialize, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "broken_drag",
    source = "test",
    equation = "C_D = 24/Re_p + sqrt(Re_p - 1e-3)",
    limits = [Limit::Stokes { cd_re: 24.0 }]
)]
struct BrokenDrag {
    /// offset added at every Re_p
    #[param(range = "[0, 1]", unit = "-")]
    offset: f64,
}

impl Default for BrokenDrag {
    fn default() -> Self {
        Self { offset: 0.0 }
    }
}

#[typetag::serde(name = "broken_drag")]
impl DragLaw for BrokenDrag {
    fn cd(&self, re_p: f64) -> f64 {
        24.0 / re_p + (re_p - 1e-3).sqrt() + self.offset
    }
    fn cd_inf(&self) -> f64 {
        0.0
    }
}

register_model!(Family::Drag, "broken_drag", DragLaw, BrokenDrag);

/// A hindrance that declares the dilute limit but tends to 2 as phi -> 0.
#[derive(Clone, Debug, Default, Serialize, Deserialize, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(name = "broken_hindrance", source = "test", equation = "f = 2 (1 - phi)^-3", limits = [Limit::Dilute])]
struct BrokenHindrance {}

#[typetag::serde(name = "broken_hindrance")]
impl Hindrance for BrokenHindrance {
    fn factor(&self, phi: f64, _re_p: f64) -> f64 {
        2.0 * (1.0 - phi).powi(-3)
    }
    fn reynolds_convention(&self) -> DragReynolds {
        DragReynolds::Interstitial
    }
    fn depends_on_reynolds(&self) -> bool {
        false
    }
}

register_model!(Family::Hindrance, "broken_hindrance", Hindrance, BrokenHindrance);

fn check(family: Family, model: &str) -> saltus::check::Report {
    saltus::ensure_registry().unwrap();
    let table = saltus::check::parse_model(model).unwrap();
    saltus::check::check(family, table, Default::default()).unwrap()
}

#[test]
fn nan_at_small_reynolds_fails_finite_with_a_shrunk_input() {
    let r = check(Family::Drag, "type = \"broken_drag\"");
    let text = r.text();
    println!("{text}");
    assert!(!r.passed());
    let finite = r.outcomes.iter().find(|o| o.name == "finite").unwrap();
    assert!(!finite.passed, "{text}");
    assert!(finite.summary.contains("C_D = NaN"), "{text}");
    // shrinking moves log10(Re_p) towards 0 (Re_p = 1), so the minimal failing input sits
    // below the 1e-3 where the law breaks, within a decade of it
    let input = finite.input.as_deref().unwrap();
    let re: f64 = input.strip_prefix("re_p = ").unwrap().split(';').next().unwrap().parse().unwrap();
    assert!((1e-4..1e-3).contains(&re), "{input}");
    assert!(input.contains("parameters as given"), "{input}");
    let stokes = r.outcomes.iter().find(|o| o.name == "limit stokes").unwrap();
    assert!(!stokes.passed && stokes.summary.contains("not finite"), "{text}");
    assert!(text.contains("FAIL  finite") && text.contains("minimal failing input: re_p = "), "{text}");
    // the checks that hold still pass
    assert!(r.outcomes.iter().find(|o| o.name == "documented").unwrap().passed, "{text}");
}

#[test]
fn hindrance_that_does_not_tend_to_one_fails_its_dilute_limit() {
    let r = check(Family::Hindrance, "type = \"broken_hindrance\"");
    let text = r.text();
    println!("{text}");
    let dilute = r.outcomes.iter().find(|o| o.name == "limit dilute").unwrap();
    assert!(!dilute.passed, "{text}");
    assert!(dilute.summary.contains("does not tend to 1"), "{text}");
    assert!(dilute.input.as_deref().unwrap().starts_with("re_p = "), "{text}");
    assert_eq!(r.failures(), 1, "{text}");
    assert!(text.ends_with("1 of 5 checks failed\n"), "{text}");
}
