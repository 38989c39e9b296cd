//! The exponent of the DEM's own fluid-phase viscosity (Fry et al. 2024 eqs 50-51):
//! eta_eq / eta_f = (1 - phi)^(-beta), fitted on a run's averaged fields, for the `fry2024`
//! viscosity closure of the two-fluid model.
//!
//! eta_eq is the fluid-phase shear stress over the fluid's shear rate (eq 50). In the DEM
//! with a clear-fluid column and the drag taken over each grain's volume
//! (`drag_velocity = "sphere_average"`), the fluid-phase stress has two parts: the column's
//! own viscous stress tau_f and the stress the drag exchange carries across each grain,
//! Fry's n<s^f>^p (eq 32); [`stress_ratio`] gives their sum over eta_f gamma_f, cell by
//! cell, from the profiles' `tau_f` and `beta` (the momentum-exchange coefficient). Then
//!
//! ```text
//! ln(eta_eq / eta_f) = beta_exp * (-ln(1 - phi))   (eq 51, no intercept: 1 at phi = 0)
//! ```
//!
//! fitted by least squares through the origin over the cells with 0.05 < phi <= 0.5 and a
//! positive shear (the range where Fry et al. fit eq 51; below 0.05 the grains' share is
//! within the noise of the column's stress, above 0.5 the bed hardly shears). Runs whose
//! fluid stress is a closure's (an Eulerian run, a DEM column with a viscosity closure)
//! or whose exchange does not cross the grains (`drag_velocity = "centre"`) do not
//! measure it: they are refused with the reason.

use saltus_closures::viscosity::fry2024::stress_ratio;
use saltus_core::scene::{DragVelocity, FluidMode, SolverKind};

use super::fields::RunFields;
use crate::least_squares;

/// The name of the fit in tables and messages.
pub const QUANTITY: &str = "viscosity exponent (Fry et al. 2024 eqs 51-52)";

/// Cells used: 0.05 < phi <= 0.5.
pub const PHI_RANGE: (f64, f64) = (0.05, 0.5);

/// The fitted exponent and what it was fitted on.
#[derive(Clone, Debug, PartialEq)]
pub struct ViscosityFit {
    /// the least-squares solution (one parameter, the exponent)
    pub solution: least_squares::Solution,
    /// lowest and highest centre of the cells used (m)
    pub z_range: (f64, f64),
}

/// Fit the exponent on `f`, or say why the run cannot give it.
pub fn fit(f: &RunFields) -> Result<ViscosityFit, String> {
    let sc = &f.scene;
    if sc.solver.kind != SolverKind::Lagrangian {
        return Err("the Eulerian run's fluid stress is the scene's viscosity closure itself".into());
    }
    if sc.solver.lagrangian.fluid == FluidMode::Off {
        return Err("the run has no fluid".into());
    }
    let closure = sc.closures.viscosity.as_ref().map_or("clear_fluid", |v| v.name());
    if closure != "clear_fluid" {
        return Err(format!(
            "the DEM's fluid column carries the scene's viscosity closure `{closure}`, so its stress is that closure's; \
             run the DEM with closures.viscosity = {{type = \"clear_fluid\"}} to measure the grains' own"
        ));
    }
    if sc.solver.lagrangian.drag_velocity != DragVelocity::SphereAverage {
        return Err(
            "with solver.lagrangian.drag_velocity = \"centre\" the exchange does not cross the grains, so the \
                    profiles hold no part of the fluid-phase stress but the column's; use \"sphere_average\""
                .into(),
        );
    }
    let col = |name: &str| f.column(name, "the viscosity exponent").map_err(|e| e.to_string());
    let (z, phi, u_f, tau_f, beta) = (col("z")?, col("phi")?, col("u_f")?, col("tau_f")?, col("beta")?);
    let gamma = saltus_solvers::output::profile_gradient(z, u_f);
    let mut x = Vec::new();
    let mut y = Vec::new();
    let mut zs = Vec::new();
    for k in 0..f.rows() {
        let g = gamma[k];
        if !(phi[k] > PHI_RANGE.0 && phi[k] <= PHI_RANGE.1 && g > 0.0 && g.is_finite()) {
            continue;
        }
        let ratio = stress_ratio(tau_f[k], beta[k], g, f.d, f.eta_f);
        if ratio > 0.0 && ratio.is_finite() {
            x.push(-(1.0 - phi[k]).ln());
            y.push(ratio.ln());
            zs.push(z[k]);
        }
    }
    let solution = least_squares::fit(&["beta0"], &[1.0], x.len(), |p| {
        Some(x.iter().zip(&y).map(|(x, y)| p[0] * x - y).collect())
    })
    .map_err(|e| format!("over the cells with {} < phi <= {} and a positive shear: {e}", PHI_RANGE.0, PHI_RANGE.1))?;
    let z_range = zs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| (a.min(z), b.max(z)));
    Ok(ViscosityFit { solution, z_range })
}

/// The `fry2024` closure table of a fit: eq 51's exponent with no Reynolds-number part
/// (`a = 0`): the run measures one exponent at its own Re_p and Shields number.
pub fn closure_table(v: &ViscosityFit) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert("type".into(), "fry2024".into());
    t.insert("beta0".into(), v.solution.params[0].into());
    t.insert("a".into(), 0.0.into());
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;
    use saltus_core::scene::Scene;
    use std::path::PathBuf;

    fn scene(set: &[&str]) -> Scene {
        saltus_closures::link();
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/fry2024/couette_bedload.toml");
        let mut all = vec!["solver.type=lagrangian".to_string(), r#"closures.viscosity={type="clear_fluid"}"#.into()];
        all.extend(set.iter().map(|s| s.to_string()));
        Scene::from_file_with(&path, &all).unwrap()
    }

    /// Profiles of a linear shear whose fluid-phase stress, the column's plus the
    /// exchange's across the grains, is eta_f (1 - phi)^-b gamma exactly: the fit gives b.
    fn fields(scene: Scene, b: f64) -> RunFields {
        let (eta_f, d) = (scene.fluid.density * scene.fluid.viscosity, scene.particles.diameter);
        let n = 60;
        let z: Vec<f64> = (0..n).map(|k| (k as f64 + 0.5) * 1e-4).collect();
        let gamma = 3.0;
        let u_f: Vec<f64> = z.iter().map(|z| gamma * z).collect();
        let phi: Vec<f64> = (0..n).map(|k| 0.6 * (1.0 - k as f64 / n as f64)).collect();
        let tau_f: Vec<f64> = phi.iter().map(|p| (1.0 - p) * eta_f * gamma).collect();
        let beta: Vec<f64> = phi
            .iter()
            .zip(&tau_f)
            .map(|(p, t)| 20.0 * (eta_f * (1.0 - p).powf(-b) * gamma - t) / (gamma * d * d))
            .collect();
        let table = Table {
            names: ["z", "phi", "u_f", "tau_f", "beta"].map(String::from).to_vec(),
            columns: vec![z, phi, u_f, tau_f, beta],
        };
        RunFields::new(PathBuf::from("profiles.csv"), table, scene).unwrap()
    }

    #[test]
    fn the_exponent_of_an_exact_power_law_is_recovered() {
        for b in [0.565, 1.764, 2.145, 3.0] {
            let f = fit(&fields(scene(&[]), b)).unwrap();
            assert!((f.solution.params[0] - b).abs() < 1e-9, "{b}: {:?}", f.solution.params);
            // the cells of 0.05 < phi <= 0.5 only
            assert_eq!(f.solution.points, 46, "{:?}", f.solution);
            assert!(f.solution.rms < 1e-9);
        }
    }

    #[test]
    fn runs_that_do_not_measure_it_are_refused_with_the_reason() {
        let centre = fit(&fields(scene(&[r#"solver.lagrangian.drag_velocity="centre""#]), 2.0)).unwrap_err();
        assert!(centre.contains("drag_velocity"), "{centre}");
        let closure = fit(&fields(scene(&[r#"closures.viscosity={type="fry2024"}"#]), 2.0)).unwrap_err();
        assert!(closure.contains("fry2024") && closure.contains("clear_fluid"), "{closure}");
        let eulerian = fit(&fields(scene(&["solver.type=eulerian"]), 2.0)).unwrap_err();
        assert!(eulerian.contains("Eulerian"), "{eulerian}");
        // too few cells in the range: a column sheared nowhere
        let mut f = fields(scene(&[]), 2.0);
        let k = f.table.names.iter().position(|n| n == "u_f").unwrap();
        f.table.columns[k].iter_mut().for_each(|u| *u = 1.0);
        let flat = fit(&f).unwrap_err();
        assert!(flat.contains("too few cells"), "{flat}");
    }
}
