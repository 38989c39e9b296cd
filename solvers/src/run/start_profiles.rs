//! The profiles a run starts from: another run's final `profiles.csv` (a sweep's
//! neighbour, or `saltus run --warm-start`), checked once and read at any height by linear
//! interpolation. The Eulerian column takes phi, u_f, u_p and theta_g from them; the DEM
//! takes u_f for its fluid column and u_p for its grains.

use serde::{Deserialize, Serialize};

use crate::output::Profiles;

/// Checked profiles: `z` increasing, every column as long and finite.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StartProfiles {
    z: Vec<f64>,
    phi: Option<Vec<f64>>,
    u_f: Vec<f64>,
    u_p: Option<Vec<f64>>,
    theta_g: Option<Vec<f64>>,
}

impl StartProfiles {
    /// The columns of `p` a start reads (`theta_g` only `with_temperature`), or why they
    /// cannot start a run: no increasing `z` of at least two cells, no `u_f`, or a column
    /// read that is not as long as `z` or holds a value that is not a finite number.
    pub fn new(p: &Profiles, with_temperature: bool) -> Result<Self, String> {
        let z = p.get("z").ok_or("the profiles have no `z` column")?;
        let ok = z.len() >= 2 && z.iter().all(|v| v.is_finite()) && z.windows(2).all(|w| w[1] > w[0]);
        if !ok {
            return Err("the profiles' `z` is not an increasing column of at least two cells".into());
        }
        let column = |name: &str| -> Result<Option<Vec<f64>>, String> {
            let Some(c) = p.get(name) else { return Ok(None) };
            if c.len() != z.len() || !c.iter().all(|v| v.is_finite()) {
                return Err(format!("the profiles' `{name}` is not {} finite numbers", z.len()));
            }
            Ok(Some(c.to_vec()))
        };
        let u_f = column("u_f")?.ok_or("the profiles have no `u_f` column")?;
        Ok(Self {
            z: z.to_vec(),
            phi: column("phi")?,
            u_f,
            u_p: column("u_p")?,
            theta_g: if with_temperature { column("theta_g")? } else { None },
        })
    }

    /// Volume fraction at `z` (clear fluid without a phi column; never negative).
    pub fn phi(&self, z: f64) -> f64 {
        self.phi.as_ref().map_or(0.0, |phi| interpolate(&self.z, phi, z).max(0.0))
    }

    /// Fluid velocity at `z` (m/s).
    pub fn u_f(&self, z: f64) -> f64 {
        interpolate(&self.z, &self.u_f, z)
    }

    /// Particle velocity at `z` (m/s); the fluid's without a u_p column.
    pub fn u_p(&self, z: f64) -> f64 {
        interpolate(&self.z, self.u_p.as_ref().unwrap_or(&self.u_f), z)
    }

    /// Granular temperature at `z` (m^2/s^2), when the profiles hold one.
    pub fn theta_g(&self, z: f64) -> Option<f64> {
        self.theta_g.as_ref().map(|t| interpolate(&self.z, t, z))
    }

    /// The bed surface of the profiles (m, in their z): the highest cell centre whose phi
    /// is at least half the largest phi, the compare table's definition; `None` without
    /// grains.
    pub fn bed_surface(&self) -> Option<f64> {
        let phi = self.phi.as_ref()?;
        let top = phi.iter().fold(0.0f64, |a, &v| a.max(v));
        if top <= 0.0 {
            return None;
        }
        phi.iter().rposition(|&v| v >= 0.5 * top).map(|k| self.z[k])
    }
}

/// Linear interpolation of `(x, y)` (x increasing, at least one point) at `at`, the end
/// values beyond.
pub fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn profiles(columns: &[(&str, &[f64])]) -> Profiles {
        Profiles { columns: columns.iter().map(|(n, v)| (n.to_string(), v.to_vec())).collect() }
    }

    #[test]
    fn interpolation_is_linear_inside_and_constant_beyond() {
        let (x, y) = ([0.0, 1.0, 3.0], [0.0, 2.0, 0.0]);
        assert_eq!(interpolate(&x, &y, -1.0), 0.0);
        assert_eq!(interpolate(&x, &y, 0.5), 1.0);
        assert_eq!(interpolate(&x, &y, 2.0), 1.0);
        assert_eq!(interpolate(&x, &y, 5.0), 0.0);
    }

    #[test]
    fn the_bed_surface_is_the_highest_cell_at_half_the_largest_packing() {
        let z = [0.5, 1.5, 2.5, 3.5, 4.5];
        let p = profiles(&[("z", &z), ("phi", &[0.6, 0.6, 0.4, 0.2, 0.0]), ("u_f", &[0.0; 5])]);
        let s = StartProfiles::new(&p, false).unwrap();
        assert_eq!(s.bed_surface(), Some(2.5));
        let clear = StartProfiles::new(&profiles(&[("z", &z), ("u_f", &[1.0; 5])]), true).unwrap();
        assert_eq!(clear.bed_surface(), None);
        assert_eq!(clear.phi(1.0), 0.0);
        // without u_p the grains move with the fluid
        assert_eq!(clear.u_p(1.0), 1.0);
    }

    #[test]
    fn profiles_that_cannot_start_a_run_are_refused_by_column() {
        let z = [0.0, 1.0];
        let no_uf = StartProfiles::new(&profiles(&[("z", &z)]), false).unwrap_err();
        assert!(no_uf.contains("`u_f`"), "{no_uf}");
        let flat = StartProfiles::new(&profiles(&[("z", &[1.0, 1.0]), ("u_f", &[0.0, 0.0])]), false).unwrap_err();
        assert!(flat.contains("increasing"), "{flat}");
        let nan = StartProfiles::new(&profiles(&[("z", &z), ("u_f", &[0.0, 0.0]), ("u_p", &[f64::NAN, 0.0])]), false)
            .unwrap_err();
        assert!(nan.contains("`u_p`") && nan.contains("finite"), "{nan}");
        let short = StartProfiles::new(&profiles(&[("z", &z), ("u_f", &[0.0])]), false).unwrap_err();
        assert!(short.contains("`u_f`"), "{short}");
        // the temperature is read only where it is taken
        let hot = profiles(&[("z", &z), ("u_f", &[0.0, 0.0]), ("theta_g", &[f64::NAN, 0.0])]);
        assert!(StartProfiles::new(&hot, false).is_ok());
        assert!(StartProfiles::new(&hot, true).unwrap_err().contains("`theta_g`"));
    }
}
