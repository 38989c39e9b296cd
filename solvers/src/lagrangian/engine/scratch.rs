//! The scratch of a DEM step, apart from the engine's state: refilled by every step,
//! never part of a checkpoint (a restored engine starts with it empty and sizes it at its
//! first step).

use super::contact_sums::ContactSums;
use super::pairs::Touching;
use crate::run::timing::Stages;

/// The stages of a DEM step whose wall time the engine counts.
pub const STAGES: [&str; 3] = ["neighbours", "pair_forces", "integration"];

/// What a DEM step refills: the external force and torque the caller sets before it, the
/// pair forces, the contact flags, the contact sums of a sampled step, and the wall time
/// of its stages.
#[derive(Clone, Debug)]
pub(crate) struct Scratch {
    /// external force per mobile particle (N), set by the caller before each step
    pub(crate) ext: [Vec<f64>; 3],
    /// external torque per mobile particle (N m)
    pub(crate) ext_torque: [Vec<f64>; 3],
    pub(crate) pair_f: Vec<[f64; 3]>,
    pub(crate) pair_t: Vec<[f64; 3]>,
    pub(crate) touching: Touching,
    /// the granular-field sums of the last sampled step ([`Dem::step_sampled`])
    pub(crate) contact: ContactSums,
    /// wall time of the step's stages ([`STAGES`])
    pub(crate) stages: Stages,
}

impl Default for Scratch {
    fn default() -> Self {
        Self::new(0)
    }
}

impl Scratch {
    /// Scratch for `nm` mobile particles.
    pub(crate) fn new(nm: usize) -> Self {
        Self {
            ext: [vec![0.0; nm], vec![0.0; nm], vec![0.0; nm]],
            ext_torque: [vec![0.0; nm], vec![0.0; nm], vec![0.0; nm]],
            pair_f: Vec::new(),
            pair_t: Vec::new(),
            touching: Touching::default(),
            contact: ContactSums::default(),
            stages: Stages::new(&STAGES),
        }
    }

    /// The per-particle buffers for `nm` mobile particles, zero (a restored engine's, or
    /// after the particles changed).
    pub(crate) fn fit(&mut self, nm: usize) {
        for v in self.ext.iter_mut().chain(self.ext_torque.iter_mut()) {
            v.clear();
            v.resize(nm, 0.0);
        }
    }
}
