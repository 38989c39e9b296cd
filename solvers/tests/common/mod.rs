//! Scene overrides and closure constructors shared by the solvers' test files.

// each test file that includes this module uses some of these only
#![allow(dead_code)]

/// A coupled bed of case 1 small enough for CI: 10 d x 10 d cell, 6 d bed, 5 d of water,
/// the mixing length of the DEM set-up (compare_case01_solvers.toml).
pub const SMALL_COUPLED_BED: [&str; 8] = [
    "solver.type=lagrangian",
    "closures.turbulence={type=\"mixing_length\", form=\"li_sawamoto\", phi_max=0.61}",
    "solver.lagrangian.length=0.06",
    "solver.lagrangian.width=0.06",
    "domain.bed_height=0.036",
    "domain.water_depth=0.03",
    "solver.lagrangian.cells=120",
    "solver.lagrangian.settle_time=0.1",
];

/// A bed of a few hundred grains of case 1 in a box of 6 x 6 diameters, deposited for
/// 0.05 s: the smallest coupled run that has every stage of the DEM step.
pub const TINY_COUPLED_BED: [&str; 6] = [
    "solver.type=\"lagrangian\"",
    "solver.lagrangian.length=0.036",
    "solver.lagrangian.width=0.036",
    "domain.bed_height=0.018",
    "domain.water_depth=0.03",
    "solver.lagrangian.settle_time=0.05",
];

/// A turbulence closure from its TOML table (`type = "laminar"`).
pub fn turbulence(text: &str) -> Box<dyn saltus_core::Turbulence> {
    saltus_closures::link();
    let t = saltus_core::scene::parse_table(text, std::path::Path::new("test")).expect("toml");
    let family = saltus_core::closure::Family::Turbulence;
    saltus_core::scene::closure_from_value(t.into(), family, std::path::Path::new("test"), "closures.turbulence")
        .expect("turbulence")
}

/// A viscosity closure from its TOML table (`type = "clear_fluid"`).
pub fn viscosity(text: &str) -> Box<dyn saltus_core::EffectiveViscosity> {
    saltus_closures::link();
    let t = saltus_core::scene::parse_table(text, std::path::Path::new("test")).expect("toml");
    let family = saltus_core::closure::Family::Viscosity;
    saltus_core::scene::closure_from_value(t.into(), family, std::path::Path::new("test"), "closures.viscosity")
        .expect("viscosity")
}
