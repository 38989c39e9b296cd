//! `saltus closure check` on every registered model of ours: all pass. The failing side
//! (a broken model and its report) is in tests/closure_check_broken.rs, whose binary
//! registers the broken models; this one sees only ours.

mod common;

use common::{assert_clean_failure, closure_check, saltus, stdout};
use saltus_core::registry;

#[test]
fn every_registered_model_passes_every_check() {
    saltus::ensure_registry().unwrap();
    let mut failed = Vec::new();
    for m in registry::models() {
        let table: toml::Value = (m.default_toml)().unwrap().parse::<toml::Table>().unwrap().into();
        let report = saltus::check::check(m.family, table, saltus::check::Options { cases: 64 }).unwrap();
        assert!(report.outcomes.len() >= 4, "{}: {}", m.name, report.text());
        if !report.passed() {
            failed.push(report.text());
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

#[test]
fn declared_limits_are_checked() {
    // einstein declares its dilute slope, so its report has a line for it
    let table: toml::Value = "type = \"einstein\"".parse::<toml::Table>().unwrap().into();
    saltus::ensure_registry().unwrap();
    let r = saltus::check::check(saltus_core::Family::Viscosity, table, Default::default()).unwrap();
    let names: Vec<&str> = r.outcomes.iter().map(|o| o.name.as_str()).collect();
    assert!(names.contains(&"limit einstein") && names.contains(&"limit dilute"), "{names:?}");
}

#[test]
fn cli_passes_with_exit_0_and_a_line_per_check() {
    let o = saltus(&["closure", "check", "--family", "drag", "--model", "type = \"dallavalle\"", "--cases", "32"]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    for check in ["documented", "toml round trip", "finite", "batch = scalar", "limit stokes", "decreasing"] {
        assert!(out.lines().any(|l| l.contains("pass") && l.contains(check)), "{check}:\n{out}");
    }
    assert!(out.contains("all 7 checks passed"), "{out}");
}

#[test]
fn cli_bad_input_exits_2_naming_what_is_wrong() {
    let e = assert_clean_failure(&closure_check("drag", "type = \"nope\""));
    assert!(e.contains("nope") && e.contains("dallavalle"), "{e}");
    let e = assert_clean_failure(&closure_check("drag", "{type = \"dallavalle\", b = 1.0}"));
    assert!(e.contains("`b`") || e.contains("b"), "{e}");
    let e = assert_clean_failure(&closure_check("dragg", "type = \"stokes\""));
    assert!(e.contains("unknown family `dragg`"), "{e}");
    let e = assert_clean_failure(&closure_check("drag", "{type = \"dallavalle\", a = -1.0}"));
    assert!(e.contains("model.a` = -1") && e.contains("(0, 100]"), "{e}");
}

#[test]
fn built_ins_declare_their_limits_and_pass_them() {
    use saltus_core::Family::{Fluctuation, Granular, Turbulence};
    saltus::ensure_registry().unwrap();
    let cases: [(saltus_core::Family, &str, &[&str]); 11] = [
        (Granular, "type = \"mu_i\"", &["limit static", "packing decreasing", "increasing"]),
        (Granular, "type = \"mu_k\"", &["limit static", "packing decreasing", "increasing"]),
        (Granular, "type = \"frictional_collisional\"", &["limit dilute"]),
        (Turbulence, "type = \"mixing_length\"", &["limit wall"]),
        (Turbulence, "type = \"mixing_length\"\nform = \"prandtl\"", &["limit wall"]),
        (Turbulence, "type = \"mixing_length\"\nbed = \"packed\"", &["limit wall"]),
        (Turbulence, "type = \"parabolic\"", &["limit wall"]),
        (Fluctuation, "type = \"drw\"", &["non-negative"]),
        (Fluctuation, "type = \"eim\"", &["non-negative"]),
        (Fluctuation, "type = \"schmidt\"", &["non-negative"]),
        (Fluctuation, "type = \"none\"", &["non-negative"]),
    ];
    for (family, text, limits) in cases {
        let table: toml::Value = text.parse::<toml::Table>().unwrap().into();
        let r = saltus::check::check(family, table, saltus::check::Options { cases: 64 }).unwrap();
        assert!(r.passed(), "{}", r.text());
        let names: Vec<&str> = r.outcomes.iter().skip(4).map(|o| o.name.as_str()).collect();
        assert_eq!(names, *limits, "{text}");
    }
    // no wall length: a grain-scale length that does not vanish at the wall
    let table: toml::Value =
        "type = \"mixing_length\"\nform = \"berzi_fraccarollo\"".parse::<toml::Table>().unwrap().into();
    let r = saltus::check::check(Turbulence, table, saltus::check::Options { cases: 16 }).unwrap();
    assert!(!r.outcomes.iter().any(|o| o.name == "limit wall"), "{}", r.text());
}
