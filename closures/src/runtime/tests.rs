//! The adapter with laws written as Rust closures over slices (what a Python function is
//! to it): the built-in laws reproduced, the scene loader's checks, failures.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use saltus_core::param::ParamRange;
use saltus_core::runtime::{self, BatchFunction, RuntimeLimit, RuntimeModel};
use saltus_core::scene::{closure_from_value, to_toml_table};
use saltus_core::{Error, Param};

use super::*;
use crate::drag::Dallavalle;
use crate::hindrance::RichardsonZaki;

type Law = dyn Fn(&[f64], &[&[f64]], &mut [&mut [f64]]) -> Result<usize, String> + Send + Sync;

struct Function {
    law: Box<Law>,
    calls: AtomicUsize,
}

impl BatchFunction for Function {
    fn evaluate(&self, params: &[f64], inputs: &[&[f64]], outputs: &mut [&mut [f64]]) -> Result<usize, String> {
        self.calls.fetch_add(1, Ordering::Relaxed);
        (self.law)(params, inputs, outputs)
    }
}

fn register(family: Family, name: &'static str, params: Vec<Param>, law: Box<Law>) -> Arc<Function> {
    let function = Arc::new(Function { law, calls: AtomicUsize::new(0) });
    runtime::register(RuntimeModel {
        family,
        name,
        source: "a test",
        equation: "a test law",
        params,
        limits: match family {
            Family::Drag => vec![RuntimeLimit::StokesParam(1), RuntimeLimit::Fixed(Limit::Decreasing)],
            _ => Vec::new(),
        },
        convention: DragReynolds::Interstitial,
        depends_on_reynolds: false,
        function: function.clone(),
        shape: Shape::Plain,
        build,
    })
    .unwrap();
    function
}

/// Dallavalle (Chassagne et al. 2023 eq 2.11a) over slices, as a user would write it.
fn dallavalle(name: &'static str) -> Arc<Function> {
    let params = vec![
        Param::new("cd_inf", 0.4, ParamRange::closed(0.0, 10.0), "-", "C_D at infinite Re_p"),
        Param::new("a", 24.4, ParamRange::open_closed(0.0, 100.0), "-", "viscous coefficient"),
    ];
    register(
        Family::Drag,
        name,
        params,
        Box::new(|p, x, out| {
            for (o, &r) in out[0].iter_mut().zip(x[0]) {
                *o = p[0] + p[1] / r;
            }
            Ok(1)
        }),
    )
}

fn table(text: &str) -> toml::Value {
    toml::Value::Table(text.parse().unwrap())
}

// the error is built once per failed load (as in saltus-solvers)
#[allow(clippy::result_large_err)]
fn drag(text: &str) -> saltus_core::Result<Box<dyn DragLaw>> {
    closure_from_value(table(text), Family::Drag, Path::new("scene.toml"), "closures.drag")
}

/// The model `name` of `family` with its defaults, as a scene loads it.
fn load<T>(family: Family, name: &str) -> Box<T>
where
    T: ?Sized + Describe + runtime::FromRuntime,
    Box<T>: serde::de::DeserializeOwned,
{
    let key = format!("closures.{family}");
    closure_from_value(table(&format!("type = \"{name}\"")), family, Path::new("s.toml"), &key).unwrap()
}

#[test]
fn a_batch_dallavalle_is_the_built_in_one() {
    let f = dallavalle("rt_dallavalle");
    let m = drag("type = \"rt_dallavalle\"\na = 24").unwrap();
    let builtin = Dallavalle { cd_inf: 0.4, a: 24.0 };
    let re: Vec<f64> = (0..200).map(|i| 10f64.powf(-8.0 + 0.08 * i as f64)).collect();
    let (mut a, mut b) = (vec![0.0; re.len()], vec![0.0; re.len()]);
    m.cd_batch(&re, &mut a);
    builtin.cd_batch(&re, &mut b);
    assert_eq!(a, b, "C_D: the same operations in the same order");
    m.cd_re_batch(&re, &mut a);
    builtin.cd_re_batch(&re, &mut b);
    for (x, y) in a.iter().zip(&b) {
        // (c + a/r) r against c r + a: a rounding apart
        assert!((x - y).abs() <= 4.0 * f64::EPSILON * y, "{x} {y}");
    }
    // Re_p = 0: C_D Re_p at RE_MIN, a + c RE_MIN
    assert!((m.cd_re(0.0) - 24.0).abs() <= 1e-11);
    assert_eq!(m.cd_inf(), 0.4);
    // one call per batch: two batches, the scalar above, and the build's C_D^inf
    assert_eq!(f.calls.load(Ordering::Relaxed), 4);
    assert_eq!(m.limits(), vec![Limit::Stokes { cd_re: 24.0 }, Limit::Decreasing]);
    assert!(m.failure().is_none());
}

#[test]
fn a_law_that_gives_cd_re_is_the_built_in_one_bit_for_bit() {
    let params = vec![
        Param::new("cd_inf", 0.4, ParamRange::closed(0.0, 10.0), "-", "C_D at infinite Re_p"),
        Param::new("a", 24.4, ParamRange::open_closed(0.0, 100.0), "-", "viscous coefficient"),
    ];
    register(
        Family::Drag,
        "rt_dallavalle_cd_re",
        params,
        Box::new(|p, x, out| {
            for (o, &r) in out[0].iter_mut().zip(x[0]) {
                *o = p[0] + p[1] / r;
            }
            if let Some(cd_re) = out.get_mut(1) {
                for (o, &r) in cd_re.iter_mut().zip(x[0]) {
                    *o = p[0] * r + p[1];
                }
            }
            Ok(out.len())
        }),
    );
    let m = drag("type = \"rt_dallavalle_cd_re\"").unwrap();
    let builtin = Dallavalle::default();
    let re: Vec<f64> = (0..200).map(|i| 10f64.powf(-8.0 + 0.08 * i as f64)).collect();
    let (mut a, mut b) = (vec![0.0; re.len()], vec![0.0; re.len()]);
    m.cd_re_batch(&re, &mut a);
    builtin.cd_re_batch(&re, &mut b);
    assert_eq!(a, b);
    assert_eq!(m.cd_re(3.0), builtin.cd_re(3.0));
    // at Re_p = 0 itself, where its C_D is +inf: the Stokes limit a
    assert_eq!(m.cd_re(0.0), 24.4);
}

#[test]
fn the_scene_loader_checks_a_runtime_model_as_a_compiled_one() {
    dallavalle("rt_checked");
    let key_of = |e: Error| match e {
        Error::Key { key, message, .. } => (key, message),
        Error::OutOfRange { key, allowed, .. } => (key, allowed),
        other => panic!("{other}"),
    };
    let (key, message) = key_of(drag("type = \"rt_checked\"\nbogus = 1.0").unwrap_err());
    assert_eq!(key, "closures.drag.bogus");
    assert!(message.contains("unknown field `bogus`") && message.contains("`cd_inf`, `a`"), "{message}");
    let (key, allowed) = key_of(drag("type = \"rt_checked\"\na = 0.0").unwrap_err());
    assert_eq!((key.as_str(), allowed.as_str()), ("closures.drag.a", "(0, 100]"));
    let (key, message) = key_of(drag("type = \"rt_checked\"\na = \"x\"").unwrap_err());
    assert_eq!(key, "closures.drag.a");
    assert!(message.contains("expected a number"), "{message}");
    match drag("type = \"rt_nowhere\"").unwrap_err() {
        Error::UnknownModel { known, .. } => {
            assert!(known.contains("dallavalle") && known.contains("rt_checked"), "{known}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn a_runtime_model_writes_its_name_and_reads_back() {
    dallavalle("rt_round_trip");
    let m = drag("type = \"rt_round_trip\"\ncd_inf = 0.5").unwrap();
    let text = to_toml_table(&m).unwrap();
    assert_eq!(text, "type = \"rt_round_trip\"\ncd_inf = 0.5\na = 24.4\n");
    let back = drag(&text).unwrap();
    assert_eq!(back.params(), m.params());
}

#[test]
fn a_failing_law_gives_nan_keeps_its_message_and_is_not_called_again() {
    let f = register(
        Family::Viscosity,
        "rt_failing",
        Vec::new(),
        Box::new(|_, x, _| if x[0].iter().any(|&p| p > 0.5) { Err("phi too large".into()) } else { Ok(1) }),
    );
    let m: Box<dyn EffectiveViscosity> = load(Family::Viscosity, "rt_failing");
    let mut out = vec![1.0; 3];
    m.ratio_batch(&[0.1, 0.6, 0.2], &mut out);
    assert!(out.iter().all(|v| v.is_nan()));
    assert_eq!(m.failure().as_deref(), Some("viscosity closure `rt_failing`: phi too large"));
    assert!(m.ratio(0.1).is_nan());
    assert_eq!(f.calls.load(Ordering::Relaxed), 1);
}

#[test]
fn a_hindrance_keeps_its_declared_convention() {
    let params = vec![Param::new("exponent", 3.1, ParamRange::closed(0.0, 10.0), "-", "zeta")];
    register(
        Family::Hindrance,
        "rt_richardson_zaki",
        params,
        Box::new(|p, x, out| {
            for (o, &phi) in out[0].iter_mut().zip(x[0]) {
                *o = (1.0 - phi).powf(-p[0]);
            }
            Ok(1)
        }),
    );
    let m: Box<dyn Hindrance> = load(Family::Hindrance, "rt_richardson_zaki");
    let builtin = RichardsonZaki::default();
    assert!(!m.depends_on_reynolds());
    assert_eq!(m.reynolds_convention(), DragReynolds::Interstitial);
    for phi in [0.0, 0.1, 0.3, 0.55] {
        assert_eq!(m.factor(phi, 3.0), builtin.factor(phi, 3.0));
    }
}

/// A laminar wall written as a user would (f Re = C, Maurin et al. 2015 section III B with
/// the laminar branch of Graf & Altinakar): the Poiseuille number C at every Re, 0 included
/// (the stress of a wall at rest stays finite), f = C / Re from the trait, one function
/// call per batch, and the compiled Graf-Altinakar law below its laminar Reynolds number.
#[test]
fn a_wall_friction_law_is_a_poiseuille_number_of_re() {
    let params = vec![Param::new("c", 48.0, ParamRange::open_closed(0.0, 1e3), "-", "f Re")];
    let f = register(
        Family::WallFriction,
        "rt_laminar_wall",
        params,
        Box::new(|p, x, out| {
            for (o, _) in out[0].iter_mut().zip(x[0]) {
                *o = p[0];
            }
            Ok(1)
        }),
    );
    let m: Box<dyn WallFriction> = load(Family::WallFriction, "rt_laminar_wall");
    let builtin = crate::wall_friction::GrafAltinakar::default();
    for re in [0.0, 1e-3, 1.0, 100.0, 600.0] {
        assert_eq!(m.poiseuille_number(re), builtin.poiseuille_number(re), "Re {re}");
    }
    assert_eq!(m.friction_factor(4.0), 12.0);
    let before = f.calls.load(Ordering::Relaxed);
    let mut re = vec![0.0, 1.0, 10.0, 1e4];
    m.poiseuille_batch(&mut re);
    assert_eq!(re, vec![48.0; 4]);
    assert_eq!(f.calls.load(Ordering::Relaxed), before + 1);
}

#[test]
fn registration_refuses_what_a_scene_could_not_use() {
    let model = |family, name: &'static str, params: Vec<Param>| RuntimeModel {
        family,
        name,
        source: "",
        equation: "",
        params,
        limits: Vec::new(),
        convention: DragReynolds::Interstitial,
        depends_on_reynolds: true,
        function: Arc::new(Function { law: Box::new(|_, _, _| Ok(1)), calls: AtomicUsize::new(0) }),
        shape: Shape::Plain,
        build,
    };
    // a granular closure is a local rheology or a coefficient set, not one plain function
    let e = runtime::register(model(Family::Granular, "rt_mu", Vec::new())).unwrap_err();
    assert!(e.contains("`granular`") && e.contains("local rheology"), "{e}");
    // two-equation turbulence has no run-time shape
    let e = runtime::register(model(Family::Turbulence, "rt_k_omega", Vec::new())).unwrap_err();
    assert!(e.contains("two-equation"), "{e}");
    let e = runtime::register(model(Family::Drag, "dallavalle", Vec::new())).unwrap_err();
    assert!(e.contains("built-in"), "{e}");
    let e = runtime::register(model(Family::Drag, "my law", Vec::new())).unwrap_err();
    assert!(e.contains("`my law`"), "{e}");
    let bad = vec![Param::new("a", -1.0, ParamRange::positive(), "-", "a")];
    let e = runtime::register(model(Family::Drag, "rt_bad_default", bad)).unwrap_err();
    assert!(e.contains("default -1 outside its range (0, inf)"), "{e}");
    // a C_D^inf that is not finite is refused when the model is built
    runtime::register(RuntimeModel {
        function: Arc::new(Function {
            law: Box::new(|_, _, out| {
                out[0].fill(f64::INFINITY);
                Ok(1)
            }),
            calls: AtomicUsize::new(0),
        }),
        ..model(Family::Drag, "rt_infinite", Vec::new())
    })
    .unwrap();
    match drag("type = \"rt_infinite\"").unwrap_err() {
        Error::Key { key, message, .. } => {
            assert_eq!(key, "closures.drag.type");
            assert!(message.contains("C_D^inf"), "{message}");
        }
        other => panic!("{other}"),
    }
    assert!(runtime::unregister(Family::Drag, "rt_infinite"));
    assert!(runtime::lookup(Family::Drag, "rt_infinite").is_none());
}
