//! A local rheology against a run: mu and phi against its control number (I for mu(I),
//! Chassagne et al. 2023 eqs 1.1-1.2; K = J + alpha I^2 for mu(K), Fry et al. 2024 eqs
//! 34-38).

use saltus_core::LocalRheology;

use super::comparison::Comparison;
use super::fields::RunFields;

/// Cells whose state can test a local rheology: phi > `phi_min`, p_p > 0, a shear rate
/// that is not 0, and finite values. The measured mu is `mu_eff` (tau_p / p_p); the
/// control number is the closure's own, from gamma_dot and p_p of the cell.
pub fn compare(label: &str, model: &dyn LocalRheology, f: &RunFields, phi_min: f64) -> anyhow::Result<Vec<Comparison>> {
    let what = "a local rheology";
    let z = f.column("z", what)?;
    let phi = f.column("phi", what)?;
    let p = f.column("p_p", what)?;
    let gamma = f.column("gamma_dot", what)?;
    let mu = f.friction(what)?;
    let (quantity_mu, quantity_phi, control) = match model.control_name() {
        "i" => ("mu(I)", "phi(I)", "I"),
        "k" => ("mu(K)", "phi(K)", "K"),
        _ => ("mu(X)", "phi(X)", "X"),
    };
    let mut c_mu = Comparison::new(label, quantity_mu, "mu [-]", control);
    let mut c_phi = Comparison::new(label, quantity_phi, "phi [-]", control);
    let (mut i_col, mut j_col): ([Vec<f64>; 2], [Vec<f64>; 2]) = Default::default();
    for k in 0..f.rows() {
        let usable = phi[k] > phi_min && p[k] > 0.0 && gamma[k] != 0.0;
        if !(usable && z[k].is_finite() && gamma[k].is_finite() && mu[k].is_finite() && p[k].is_finite()) {
            continue;
        }
        let s = f.state(gamma[k], p[k]);
        let x = model.control_number(&s);
        if !x.is_finite() {
            continue;
        }
        let (i, j) = (s.inertial_number(), s.viscous_number());
        if !(i.is_finite() && j.is_finite()) {
            continue;
        }
        if c_mu.push(z[k], x, mu[k], model.friction(x)) {
            i_col[0].push(i);
            j_col[0].push(j);
        }
        if c_phi.push(z[k], x, phi[k], model.packing(x)) {
            i_col[1].push(i);
            j_col[1].push(j);
        }
    }
    for (c, (i, j)) in [&mut c_mu, &mut c_phi].into_iter().zip(i_col.into_iter().zip(j_col)) {
        // the control number's own column is not repeated (mu(I) has I already)
        c.extra = [("I", i), ("J", j)].into_iter().filter(|(name, _)| *name != control).collect();
    }
    Ok(vec![c_mu, c_phi])
}
