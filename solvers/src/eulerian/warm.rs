//! A warm start: the column started from the profiles of another run (a neighbouring
//! point of a sweep) instead of from rest.

use super::solver::Eulerian;
use crate::output::Profiles;
use crate::run::start_profiles::StartProfiles;

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
        let p = StartProfiles::new(p, self.kinetic)?;
        let centres = self.op.grid().centres().to_vec();
        let dz = self.op.grid().dz();
        for (i, &zc) in centres.iter().enumerate() {
            self.s.phi[i] = p.phi(zc);
            self.s.uf[i] = p.u_f(zc);
            self.s.up[i] = p.u_p(zc);
            if let Some(v) = p.theta_g(zc) {
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
