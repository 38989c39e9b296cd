//! A kinetic-theory closure against a run (Chassagne et al. 2023 section 3): the radial
//! distribution g0 extracted from the pressure against each radial-distribution model
//! (eqs 2.19, 2.23, 3.1-3.3), the collisional dissipation (eq 2.22 with F4'), the shear
//! viscosity and the heat flux against the transport coefficients (eqs 2.20-2.21, 3.7,
//! 3.10), the drag dissipation against eqs 2.25 and 3.13.

use saltus_closures::granular::kinetic::{
    ChialvoSundaresanFrictionG0, ChialvoSundaresanG0, DragDissipation, RadialDistribution,
};
use saltus_core::grain::carnahan_starling;
use saltus_core::{KineticCoefficients, KineticTheory};
use saltus_solvers::inputs::{DragKernel, DragPoints};
use saltus_solvers::output::profile_gradient;

use super::comparison::Comparison;
use super::fields::RunFields;
use crate::least_squares::LeastSquares;

/// What a kinetic closure's comparisons found besides the comparisons: the coefficient a
/// of eq 3.2 fitted to the extracted g0 over all the cells used and over three bands of
/// phi, and the value eq 3.3 gives at the grains' mu_p.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct G0Fit {
    /// relative least-squares a (weights 1/g0^2) of g0 - g0_CS = a phi^2 / (phi_max - phi)^1.5 over the cells used
    pub a: f64,
    /// its standard error from the residuals, sqrt(SSR / (n - 1) / Sxx) (NaN below two
    /// cells): a lower bound, since neighbouring slices of a DEM profile are correlated
    pub a_stderr: f64,
    /// a(mu_p) of eq 3.3 with the paper's a0 = 0.58, a_max = 3.70, delta = 0.54
    pub a_eq33: f64,
    /// the grains' interparticle friction mu_p
    pub mu_p: f64,
    /// cells of the fit
    pub cells: usize,
    /// the same fit in each band of [`G0_FIT_BANDS`]
    pub bands: [BandFit; 3],
}

/// The phi bands of the banded fits: the dilute layer, where the friction term of eq 3.2
/// is under a third of g0 for a ~ 3 and a rests on the extracted g0's last digits; the
/// transition; and the dense layer, where that term carries most of g0. The fit over all
/// cells weighs them by their number, so how a varies across the bands says how much the
/// single a depends on the window (Chassagne et al. do not state theirs).
pub const G0_FIT_BANDS: [(f64, f64); 3] = [(0.0, 0.3), (0.3, 0.5), (0.5, 1.0)];

/// The fit of a over the cells with phi in [phi_lo, phi_hi).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandFit {
    /// lower bound of phi (inclusive)
    pub phi_lo: f64,
    /// upper bound of phi (exclusive)
    pub phi_hi: f64,
    /// fitted a (NaN without cells)
    pub a: f64,
    /// its standard error (NaN below two cells)
    pub a_stderr: f64,
    /// cells in the band
    pub cells: usize,
}

/// Relative least squares of y = a x through the origin over `points` (x, y) and the
/// standard error of a, sqrt(SSR / (n - 1) / Sxx): (a, stderr, n), NaN for what the points
/// do not determine (a without cells or with every x = 0, the error below two cells).
fn slope(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64, usize) {
    let (x, y): (Vec<f64>, Vec<f64>) = points.unzip();
    let n = x.len();
    let fit = LeastSquares::new(&["a"], &[0.0], n)
        .min_points(1)
        .jacobian(|_| Some(x.clone()))
        .linear()
        .solve(|p| Some(x.iter().zip(&y).map(|(x, y)| p[0] * x - y).collect()));
    match fit {
        Ok(s) => (s.params[0], s.stderr_independent[0], n),
        Err(_) => (f64::NAN, f64::NAN, n),
    }
}

/// A cell's state for the kinetic comparisons.
#[derive(Clone)]
struct Cell {
    k: usize,
    phi: f64,
    p: f64,
    t: f64,
    coef: KineticCoefficients,
}

/// Every comparison of kinetic closure `kt` on the cells with `phi_min` < phi < phi_max
/// (where the coefficients diverge), p_p > 0, T > 0 and finite values, with the g0 fit.
pub fn compare(
    label: &str,
    kt: &dyn KineticTheory,
    f: &RunFields,
    phi_min: f64,
) -> anyhow::Result<(Vec<Comparison>, G0Fit)> {
    let what = "a kinetic-theory closure";
    let z = f.column("z", what)?;
    let phi = f.column("phi", what)?;
    let p = f.column("p_p", what)?;
    let temp = f.column("theta_g", what)?;
    let gamma = f.column("gamma_dot", "the shear viscosity")?;
    let mu = f.friction("the shear viscosity")?;
    let gamma_diss = f.column("dissipation", "the collisional dissipation")?;
    let q = f.column("heat_flux", "the heat flux")?;
    let j_int = f.column("drag_dissipation", "the drag dissipation")?;
    let beta = f.column("beta", "the drag dissipation and the saltation correction")?;
    let (u_f, u_p) = (f.column("u_f", "the drag dissipation")?, f.column("u_p", "the drag dissipation")?);
    let w_p = f.optional("w_p");
    let (rho_p, d) = (f.rho_p, f.d);
    let salt = kt.saltation_enabled();
    let cells: Vec<Cell> = (0..f.rows())
        .filter(|&k| phi[k] > phi_min && phi[k] < kt.phi_max() && p[k] > 0.0 && temp[k] > 0.0)
        .filter(|&k| [z[k], phi[k], p[k], temp[k]].iter().all(|v| v.is_finite()))
        .map(|k| {
            let s = kt.saltation_input(phi[k], temp[k], beta[k], rho_p, d);
            let coef = kt.coefficients(phi[k], (salt && s.k_drag.is_finite()).then_some(&s));
            Cell { k, phi: phi[k], p: p[k], t: temp[k], coef }
        })
        .collect();

    // the collisional layer: above the highest cell where the closure's enduring-contact
    // pressure acts. Below it (the packed bed, and the fixed rough layer of a DEM whose
    // phi can dip under the onset) contacts last and T -> 0, so eq 3.1 and the viscosity
    // ratio divide a quasi-static stress by a vanishing temperature
    let bed_top = (0..f.rows()).filter(|&k| phi[k].is_finite() && kt.elastic_pressure(phi[k]) > 0.0).max();
    let collisional: Vec<Cell> = cells.iter().filter(|c| bed_top.is_none_or(|b| c.k > b)).cloned().collect();
    let (mut out, fit) = radial_distribution(label, kt, f, &collisional, z);

    let mut c = Comparison::new(label, "Gamma", "Gamma [W/m^3]", "phi");
    for cell in cells.iter().filter(|c| gamma_diss[c.k].is_finite()) {
        c.push(z[cell.k], cell.phi, gamma_diss[cell.k], kt.dissipation(&cell.coef, rho_p, d, cell.t));
    }
    out.push(c);

    // the kinetic viscosity alone: cells without enduring-contact pressure (p_el = 0)
    let mut c = Comparison::new(label, "viscosity F2", "eta / (rho_p d sqrt(T)) [-]", "phi");
    for cell in &collisional {
        let (g, k) = (gamma[cell.k], cell.k);
        if g == 0.0 || !g.is_finite() || !mu[k].is_finite() {
            continue;
        }
        let measured = kt.viscosity_coefficient(mu[k] * cell.p, g, rho_p, d, cell.t);
        c.push(z[k], cell.phi, measured, cell.coef.f2);
    }
    out.push(c);

    let dtdz = profile_gradient(z, temp);
    let mut c = Comparison::new(label, "heat flux", "q_z [W/m^2]", "phi");
    let mut gradient = Vec::new();
    for cell in cells.iter().filter(|c| q[c.k].is_finite() && dtdz[c.k].is_finite()) {
        let kappa = kt.conductivity(&cell.coef, rho_p, d, cell.t.sqrt());
        if c.push(z[cell.k], cell.phi, q[cell.k], -kappa * dtdz[cell.k]) {
            gradient.push(dtdz[cell.k]);
        }
    }
    c.extra = vec![("dT/dz", gradient)];
    out.push(c);

    out.extend(drag_dissipation(label, f, &cells, [z, phi, u_f, u_p, beta, j_int], w_p)?);
    Ok((out, fit))
}

/// g0 extracted from the pressure ([`KineticTheory::radial_distribution_of_pressure`]:
/// eq 3.1 with the closure's e and the total pressure, as Chassagne et al. do where the
/// elastic pressure vanishes, above the packed bed) and held against the closure's own g0
/// and the library's models, with the fit of a in eq 3.2 against
/// [`KineticTheory::radial_distribution_regressor`].
fn radial_distribution(
    label: &str,
    kt: &dyn KineticTheory,
    f: &RunFields,
    cells: &[Cell],
    z: &[f64],
) -> (Vec<Comparison>, G0Fit) {
    let phi_max = kt.phi_max();
    let mu_p = f.scene.particles.friction;
    let models: [(&'static str, RadialDistribution); 3] = [
        ("g0 carnahan_starling", RadialDistribution::CarnahanStarling {}),
        ("g0 chialvo_sundaresan", RadialDistribution::ChialvoSundaresan(ChialvoSundaresanG0::default())),
        (
            "g0 chialvo_sundaresan_friction",
            RadialDistribution::ChialvoSundaresanFriction(ChialvoSundaresanFrictionG0::default()),
        ),
    ];
    let mut own = Comparison::new(label, "g0 closure", "g0 [-]", "phi");
    let mut library: Vec<Comparison> =
        models.iter().map(|(name, _)| Comparison::new(label, name, "g0 [-]", "phi")).collect();
    // (phi, x, y) of the relative regression y = a x, per cell
    let mut points: Vec<(f64, f64, f64)> = Vec::with_capacity(cells.len());
    for cell in cells {
        let c = &cell.coef;
        let g0 = kt.radial_distribution_of_pressure(c, cell.phi, cell.p, f.rho_p, cell.t);
        if !(g0.is_finite() && c.g0.is_finite() && cell.phi < phi_max) {
            continue;
        }
        let zk = z[cell.k];
        own.push(zk, cell.phi, g0, c.g0);
        for (cmp, (_, m)) in library.iter_mut().zip(&models) {
            cmp.push(zk, cell.phi, g0, m.g0(cell.phi, phi_max, mu_p));
        }
        // relative least squares: g0 spans three decades between the saltation layer
        // and the bed, and an absolute fit would be the densest cell's alone
        let x = kt.radial_distribution_regressor(cell.phi) / g0;
        points.push((cell.phi, x, (g0 - carnahan_starling(cell.phi)) / g0));
    }
    let a_eq33 = RadialDistribution::default().coefficient_a(mu_p);
    let (a, a_stderr, cells) = slope(points.iter().map(|&(_, x, y)| (x, y)));
    let bands = G0_FIT_BANDS.map(|(phi_lo, phi_hi)| {
        let (a, a_stderr, cells) =
            slope(points.iter().filter(|p| p.0 >= phi_lo && p.0 < phi_hi).map(|&(_, x, y)| (x, y)));
        BandFit { phi_lo, phi_hi, a, a_stderr, cells }
    });
    let fit = G0Fit { a, a_stderr, a_eq33, mu_p, cells, bands };
    let mut out = vec![own];
    out.extend(library);
    (out, fit)
}

/// J_int measured (eq 2.30) against -c_J phi (1 - phi) K T = -c_J beta T with c_J = 3
/// (eq 2.25) and c_J = 3 + 2 C_D^inf / C_D (eq 3.13), C_D of the scene's drag and
/// hindrance at the cell's mean slip, Re_p = |u_f - u_p, w_p / (1 - phi)| d / nu_f as the
/// Eulerian solver evaluates it.
fn drag_dissipation(
    label: &str,
    f: &RunFields,
    cells: &[Cell],
    [z, phi, u_f, u_p, beta, j_int]: [&[f64]; 6],
    w_p: Option<&[f64]>,
) -> anyhow::Result<Vec<Comparison>> {
    let cl = &f.scene.closures;
    let (Some(drag), Some(hindrance)) = (cl.drag.as_deref(), cl.hindrance.as_deref()) else {
        anyhow::bail!("{}: the scene has no drag or hindrance closure", f.profiles_path.display());
    };
    let kernel = DragKernel::new(drag, hindrance);
    let used: Vec<&Cell> =
        cells.iter().filter(|c| [beta[c.k], j_int[c.k], u_f[c.k], u_p[c.k]].iter().all(|v| v.is_finite())).collect();
    let nu = f.scene.fluid.viscosity;
    let (mut phis, mut re) = (Vec::with_capacity(used.len()), Vec::with_capacity(used.len()));
    for c in &used {
        let p = phi[c.k].clamp(0.0, 1.0 - 1e-12);
        let w = w_p.map_or(0.0, |w| if w[c.k].is_finite() { w[c.k] } else { 0.0 });
        let slip = saltus_solvers::inputs::mean_slip(u_f[c.k], u_p[c.k], w, p);
        phis.push(p);
        re.push(slip * f.d / nu);
    }
    let mut points = DragPoints::new(used.len());
    kernel.evaluate(&phis, &re, &mut points);
    let cd_inf = drag.cd_inf();
    let mut linear = Comparison::new(label, "J_int eq 2.25", "J_int [W/m^3]", "phi");
    let mut quadratic = Comparison::new(label, "J_int eq 3.13", "J_int [W/m^3]", "phi");
    for (i, c) in used.iter().enumerate() {
        let cd = points.cd_re[i] / points.re_star[i];
        let bt = beta[c.k] * c.t;
        let zk = z[c.k];
        linear.push(zk, c.phi, j_int[c.k], -DragDissipation::Linear.factor(cd_inf, cd) * bt);
        quadratic.push(zk, c.phi, j_int[c.k], -DragDissipation::Quadratic.factor(cd_inf, cd) * bt);
    }
    Ok(vec![linear, quadratic])
}

#[cfg(test)]
mod tests {
    use super::slope;

    /// Two cells at the same x with residuals +e and -e: a is their mean exactly and its
    /// standard error is e (SSR = 2 e^2, n - 1 = 1, Sxx = 2 x^2 with x = 1).
    #[test]
    fn the_slope_and_its_standard_error_of_symmetric_residuals() {
        let (a, e) = (2.5, 0.3);
        let (fit, se, n) = slope([(1.0, a + e), (1.0, a - e)].into_iter());
        assert_eq!(n, 2);
        assert!((fit - a).abs() < 1e-15 && (se - e).abs() < 1e-15, "{fit} {se}");
        // exact data: no error; one cell: no error estimate; no cell: no fit
        let (fit, se, _) = slope([(0.5, 1.0), (2.0, 4.0), (3.0, 6.0)].into_iter());
        assert!((fit - 2.0).abs() < 1e-15 && se < 1e-15);
        assert!(slope([(1.0, 2.0)].into_iter()).1.is_nan());
        assert!(slope(std::iter::empty()).0.is_nan());
        // every x = 0: no slope
        assert!(slope([(0.0, 1.0), (0.0, 2.0)].into_iter()).0.is_nan());
    }

    /// Scattered cells: the slope and its error are the closed form through the origin,
    /// a = Sxy / Sxx and sqrt(SSR / (n - 1) / Sxx), to round-off.
    #[test]
    fn the_slope_is_the_closed_form_through_the_origin() {
        let points: Vec<(f64, f64)> = (1..=40)
            .map(|k| {
                let x = 0.013 * k as f64 + 0.002 * ((k * 7 % 11) as f64);
                (x, 2.7 * x + 0.01 * ((k * 5 % 13) as f64 - 6.0))
            })
            .collect();
        let sxy: f64 = points.iter().map(|(x, y)| x * y).sum();
        let sxx: f64 = points.iter().map(|(x, _)| x * x).sum();
        let a = sxy / sxx;
        let ssr: f64 = points.iter().map(|(x, y)| (y - a * x).powi(2)).sum();
        let se = (ssr / 39.0 / sxx).sqrt();
        let (fit, fit_se, n) = slope(points.iter().copied());
        assert_eq!(n, 40);
        assert!((fit - a).abs() <= 1e-14 * a && (fit_se - se).abs() <= 1e-12 * se, "{fit} {a} {fit_se} {se}");
    }
}
