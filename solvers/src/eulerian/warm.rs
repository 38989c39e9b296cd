//! A warm start: the column started from the profiles of another run (a neighbouring
//! point of a sweep) instead of from rest.

use super::solver::Eulerian;
use crate::output::Profiles;
use crate::run::checkpoint::Restart;
use crate::run::start_profiles::StartProfiles;

/// Why the column cannot start from the checkpoint `r`: it starts from profiles.
pub fn checkpoint_refusal(r: &Restart) -> String {
    format!("{}: the Eulerian column starts from profiles, not from a checkpoint", r.file.display())
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
        if self.state.kw.is_some() {
            return Err("the k and omega of a two-equation turbulence closure are not in the profiles".into());
        }
        let p = StartProfiles::new(p, self.params.kinetic)?;
        let centres = self.params.op.grid().centres().to_vec();
        let dz = self.params.op.grid().dz();
        for (i, &zc) in centres.iter().enumerate() {
            self.state.phi[i] = p.phi(zc);
            self.state.uf[i] = p.u_f(zc);
            self.state.up[i] = p.u_p(zc);
            if let Some(v) = p.theta_g(zc) {
                if v > 0.0 {
                    self.state.temp[i] = v;
                }
            }
        }
        let mass = self.state.sediment_height(dz);
        let clear = self.state.mass0 <= 0.0;
        if clear && mass > 0.0 {
            return Err("the profiles hold sediment and the scene none".into());
        }
        if !clear {
            if mass.is_nan() || mass <= 0.0 {
                return Err("the profiles hold no sediment and the scene some".into());
            }
            let scale = self.state.mass0 / mass;
            self.state.phi.iter_mut().for_each(|v| *v *= scale);
        }
        self.state.flux.iter_mut().for_each(|v| *v = 0.0);
        self.state.drift_flux.iter_mut().for_each(|v| *v = 0.0);
        self.evaluate().map_err(|b| format!("the warm state: {b}"))
    }
}
