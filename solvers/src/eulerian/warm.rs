//! A warm start: the column started from the profiles of another run (a neighbouring
//! point of a sweep) instead of from rest.

use super::solver::Eulerian;
use crate::output::Profiles;

/// Linear interpolation of `(x, y)` (x increasing) at `at`, the end values beyond.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    let n = x.len();
    if at <= x[0] {
        return y[0];
    }
    if at >= x[n - 1] {
        return y[n - 1];
    }
    let k = x.partition_point(|&v| v <= at).clamp(1, n - 1);
    let t = (at - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] + t * (y[k] - y[k - 1])
}

impl Eulerian<'_> {
    /// Take phi, u_f, u_p (and theta_g of a kinetic closure) from `p`, interpolated in z
    /// onto this grid, the column above the profiles' top filled with their top values.
    /// phi is scaled so that the column holds the sediment of this scene (its
    /// bed_phi x bed_height), so that a neighbour with another inventory does not change
    /// this one's; a scene without sediment takes clear fluid. A profile without phi is
    /// clear fluid, without u_p the grains move with the fluid, without theta_g the
    /// scene's own temperature stays. A two-equation turbulence closure's k and omega are
    /// not in the profiles: refused.
    pub(super) fn warm_start_from(&mut self, p: &Profiles) -> Result<(), String> {
        if self.s.kw.is_some() {
            return Err("the k and omega of a two-equation turbulence closure are not in the profiles".into());
        }
        let z = p.get("z").ok_or("the profiles have no `z` column")?;
        let ok = z.len() >= 2 && z.iter().all(|v| v.is_finite()) && z.windows(2).all(|w| w[1] > w[0]);
        if !ok {
            return Err("the profiles' `z` is not an increasing column of at least two cells".into());
        }
        let column = |name: &str| -> Result<Option<&[f64]>, String> {
            let Some(c) = p.get(name) else { return Ok(None) };
            if c.len() != z.len() || !c.iter().all(|v| v.is_finite()) {
                return Err(format!("the profiles' `{name}` is not {} finite numbers", z.len()));
            }
            Ok(Some(c))
        };
        let uf = column("u_f")?.ok_or("the profiles have no `u_f` column")?;
        let (phi, up) = (column("phi")?, column("u_p")?.unwrap_or(uf));
        let temp = if self.kinetic { column("theta_g")? } else { None };
        let centres = self.op.grid().centres().to_vec();
        let dz = self.op.grid().dz();
        for (i, &zc) in centres.iter().enumerate() {
            self.s.phi[i] = phi.map_or(0.0, |phi| interpolate(z, phi, zc).max(0.0));
            self.s.uf[i] = interpolate(z, uf, zc);
            self.s.up[i] = interpolate(z, up, zc);
            if let Some(t) = temp {
                let v = interpolate(z, t, zc);
                if v > 0.0 {
                    self.s.temp[i] = v;
                }
            }
        }
        let mass = self.s.sediment_height(dz);
        let clear = self.s.mass0 <= 0.0;
        if clear && mass > 0.0 {
            return Err("the profiles hold sediment and the scene none".into());
        }
        if !clear {
            if mass.is_nan() || mass <= 0.0 {
                return Err("the profiles hold no sediment and the scene some".into());
            }
            let scale = self.s.mass0 / mass;
            self.s.phi.iter_mut().for_each(|v| *v *= scale);
        }
        self.s.flux.iter_mut().for_each(|v| *v = 0.0);
        self.s.drift_flux.iter_mut().for_each(|v| *v = 0.0);
        self.evaluate().map_err(|b| format!("the warm state: {b}"))
    }
}

#[cfg(test)]
mod tests {
    use super::interpolate;

    #[test]
    fn interpolation_is_linear_inside_and_constant_beyond() {
        let (x, y) = ([0.0, 1.0, 3.0], [0.0, 2.0, 0.0]);
        assert_eq!(interpolate(&x, &y, -1.0), 0.0);
        assert_eq!(interpolate(&x, &y, 0.5), 1.0);
        assert_eq!(interpolate(&x, &y, 2.0), 1.0);
        assert_eq!(interpolate(&x, &y, 5.0), 0.0);
    }
}
