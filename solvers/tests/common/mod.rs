//! Scene overrides shared by the Lagrangian test files.

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
