//! The DEM's averaged granular fields: stresses split into kinetic and contact parts,
//! fluctuation-energy flux, collisional and drag dissipation, shear rate, inertial and
//! viscous numbers, effective friction and coordination (Chassagne et al. 2023 section
//! 2.2, eqs 2.27-2.30, after Babic 1997, Goldhirsch 2010 and Patz et al. 2015; Fry et al.
//! 2024 section II for I, J and mu).
//!
//! # Averaging
//!
//! The slices are those of phi (Maurin et al. 2015 eq A1, Chassagne Appendix A): the
//! fluid cells, over the whole periodic area A, of height dz and volume V = A dz. The
//! fields are sampled at the averaging samples of [`super::statistics`] (every fluid update
//! from `stats_start`, or every `fluid_period` of a dry run that asks for them) and
//! averaged over space and time together, like phi: every sum below is summed over the
//! samples and divided by their number S and by V.
//!
//! * Particle terms carry the exact volume share V_pc of sphere p in slice c, like phi
//!   (kinetic stress, heat flux) or the share V_pc / V_p (drag, particle count).
//! * Contact terms (stress, heat flux, dissipation, contact count) are divided between
//!   the slices that the contact's branch vector reaches, each end smeared over its
//!   grain like phi ([`Slices::branch`]). The branch vector runs centre to centre, also
//!   to a fixed particle; for a flat wall it runs from the centre to the wall plane. The
//!   terms that carry the branch's rise (P_zz, P_xz, P_yz, heat flux) take the signed
//!   share whose divergence is the contact force as phi weights it, which makes the
//!   momentum balance hold slice by slice; the others (P_xx, P_yy, dissipation, count)
//!   take a share that is never negative, the same one wherever the signed share is
//!   not negative (two grains of one size), so that a count or a dissipation is never
//!   below zero in a slice where grains of two sizes touch.
//!
//! # Definitions and sign conventions
//!
//! Stresses are written **compressive positive**, as a pressure: P_ij = -sigma_ij with
//! sigma the Cauchy stress (tension positive) of Chassagne eq 2.27. With f the force on
//! particle a from particle b and b = x_b - x_a the branch vector (a < b: each contact
//! once), in slice c:
//!
//! ```text
//! P_ij = rho_p phi <v'_i v'_j>  -  (1/V) sum_contacts w_c f_i b_j
//!        \___ kinetic ______/      \________ contact ___________/
//! p_p = P_zz,   tau_p = -P_xz,   sigma_xx = P_xx, sigma_yy = P_yy, sigma_zz = P_zz
//! ```
//!
//! (Chassagne's eq 2.27 writes the contact sum with the force on p by q and
//! b = x_q - x_p and a minus sign in front of both terms: with the force on p by q it is
//! the tension-positive stress when the branch runs x_p - x_q; the form above is the
//! virial's, P = (1/V) [sum m v' v' + sum_pairs f^{a<-b} (x_a - x_b)], whose trace is the
//! kinetic-theory pressure.) tau_p = sigma_xz is positive when the grains resist a flow in
//! +x whose velocity grows with z. v' = v - `<v>` with `<v>` the slice's mean over space and
//! time, so the kinetic stress holds the temporal fluctuations of the mean too (that is
//! the momentum flux of the time-averaged balance).
//!
//! * `theta_g` (the existing column): (<v'_x^2> + <v'_y^2> + <v'_z^2>) / 3.
//! * `heat_flux` q_z (Chassagne eq 2.28, here the flux of fluctuation energy, positive
//!   upward), the contact part being the symmetric (Goldhirsch 2010) rate of work across
//!   the slice, taken relative to the slice's mean velocity (the last term); Chassagne's
//!   sign convention (the same minus signs as eq 2.27) makes it -q_z:
//!
//!   ```text
//!   q_z = (1/2) rho_p phi <v'_z v'_i v'_i> + (1/V) sum w_c (-b_z) f.(v_a + v_b)/2
//!         - <v_j> P^contact_jz
//!   ```
//! * `dissipation` Gamma (eq 2.29, W m^-3, >= 0): (1/V) sum w_c D_c with D_c the power the
//!   contact law dissipates ([`crate::lagrangian::engine::contact`]: dashpot c v_n^2 plus Coulomb slip), walls
//!   and fixed particles included. Eq 2.29 sums -f.(v_p - v_q)/2 over the translational
//!   velocities, which also counts the energy exchanged with the rotations and stored in
//!   the springs; those average out (rotation: at steady state) and what remains is D.
//! * `drag_dissipation` J_int (eq 2.30, W m^-3): n <f_D,i v'_i> =
//!   (1/V) [sum (V_pc / V_p) F_D.v - <v_i> sum (V_pc / V_p) F_D,i] over the mobile
//!   particles, with the paper's sign (negative where the drag damps the fluctuations,
//!   eq 2.25).
//! * `gamma_dot` d<v_x>/dz by centred differences (one-sided at the ends of the
//!   particle-holding slices); `inertial_number` I = |gamma_dot| d / sqrt(p_p / rho_p)
//!   (Chassagne eq 1.1, Fry eq 16); `viscous_number` J = eta_f |gamma_dot| / p_p (Fry
//!   eq 17; eta_f = rho_f nu_f, undefined without fluid); `mu_eff` = tau_p / p_p.
//! * `coordination` Z: 2 (contacts in the slice) / (particles in the slice), contacts
//!   counted along their branch like the stress (a wall contact counts once), particles
//!   by their volume share V_pc / V_p. Fixed particles are counted but their contacts with
//!   each other are not computed: Z is low where they are.
//!
//! A value that a slice cannot define (no particle volume there, or p_p <= 0 for I, J and
//! mu_eff) is NaN here and an empty cell in profiles.csv.

use saltus_core::grain::ball_volume;
use serde::{Deserialize, Serialize};

use super::statistics::Stats;
use crate::lagrangian::engine::contact_sums::*;
use crate::lagrangian::engine::particles::Particles;
use crate::lagrangian::engine::slicing::sphere_slices;

/// Running sums of the granular fields over the averaging samples (the particle moments
/// phi and the kinetic stress share with the profiles are in [`Stats`]).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct GranularStats {
    /// samples taken
    pub samples: usize,
    /// contact sums, slice-major ([`CONTACT_FIELDS`] per slice)
    contact: Vec<f64>,
    /// sum V_pc v_y v_z
    vyz: Vec<f64>,
    /// sum V_pc v_z |v|^2
    vz_v2: Vec<f64>,
    /// sum V_pc / V_p (particles)
    count: Vec<f64>,
    /// sum (V_pc / V_p) F_D of the mobile particles
    drag: [Vec<f64>; 3],
    /// sum (V_pc / V_p) F_D.v of the mobile particles
    drag_v: Vec<f64>,
}

/// The time-averaged granular fields per slice (NaN where undefined); see the module
/// documentation for the definitions.
#[derive(Clone, Debug, Default)]
pub struct GranularAverages {
    /// particle pressure P_zz (Pa) and its kinetic and contact parts
    pub p_p: [Vec<f64>; 3],
    /// particle shear stress -P_xz (Pa) and its kinetic and contact parts
    pub tau_p: [Vec<f64>; 3],
    /// normal stresses P_xx, P_yy, P_zz (Pa, compressive positive)
    pub sigma: [Vec<f64>; 3],
    /// fluctuation-energy flux q_z (W m^-2, positive upward)
    pub heat_flux: Vec<f64>,
    /// collisional dissipation Gamma (W m^-3)
    pub dissipation: Vec<f64>,
    /// drag dissipation J_int (W m^-3)
    pub drag_dissipation: Vec<f64>,
    /// drag force per unit volume on the mobile particles, n <f_D> (N m^-3)
    pub drag: [Vec<f64>; 3],
    /// d<v_x>/dz (1/s)
    pub gamma_dot: Vec<f64>,
    /// inertial number
    pub inertial_number: Vec<f64>,
    /// viscous number
    pub viscous_number: Vec<f64>,
    /// tau_p / p_p
    pub mu_eff: Vec<f64>,
    /// contacts per particle
    pub coordination: Vec<f64>,
}

impl GranularAverages {
    /// The profiles.csv columns, in order.
    pub fn columns(&self) -> [(&'static str, &[f64]); 17] {
        [
            ("p_p", &self.p_p[0]),
            ("p_p_kinetic", &self.p_p[1]),
            ("p_p_contact", &self.p_p[2]),
            ("tau_p", &self.tau_p[0]),
            ("tau_p_kinetic", &self.tau_p[1]),
            ("tau_p_contact", &self.tau_p[2]),
            ("sigma_xx", &self.sigma[0]),
            ("sigma_yy", &self.sigma[1]),
            ("sigma_zz", &self.sigma[2]),
            ("heat_flux", &self.heat_flux),
            ("dissipation", &self.dissipation),
            ("drag_dissipation", &self.drag_dissipation),
            ("gamma_dot", &self.gamma_dot),
            ("inertial_number", &self.inertial_number),
            ("viscous_number", &self.viscous_number),
            ("mu_eff", &self.mu_eff),
            ("coordination", &self.coordination),
        ]
    }
}

/// The material the averages need.
#[derive(Clone, Copy, Debug)]
pub struct FieldScales {
    /// particle density (kg/m^3)
    pub rho_p: f64,
    /// particle diameter (m)
    pub d: f64,
    /// dynamic viscosity of the fluid (Pa s), `None` without fluid
    pub eta_f: Option<f64>,
}

impl GranularStats {
    /// Empty sums over `n` slices.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self {
            samples: 0,
            contact: vec![0.0; n * CONTACT_FIELDS],
            vyz: z(),
            vz_v2: z(),
            count: z(),
            drag: [z(), z(), z()],
            drag_v: z(),
        }
    }

    /// Number of slices.
    pub fn len(&self) -> usize {
        self.count.len()
    }

    /// Whether every sum holds `n` slices (a checkpoint's, before it is used).
    pub fn fits(&self, n: usize) -> bool {
        let per_slice =
            [&self.vyz, &self.vz_v2, &self.count, &self.drag[0], &self.drag[1], &self.drag[2], &self.drag_v];
        self.contact.len() == n * CONTACT_FIELDS && per_slice.iter().all(|v| v.len() == n)
    }

    /// Whether there is no slice.
    pub fn is_empty(&self) -> bool {
        self.count.is_empty()
    }

    /// Add one sample: the contact sums of the sampled step and the particle moments of
    /// `p` on `slices`, with `drag(a)` the fluid force on mobile particle a (N).
    pub fn add(&mut self, contacts: &ContactSums, p: &Particles, slices: &Slices, drag: impl Fn(usize) -> [f64; 3]) {
        contacts.add_to(&mut self.contact);
        let n = self.len();
        for a in 0..p.len() {
            let (zc, r) = (p.z[a] - slices.base, p.radius[a]);
            let vp = ball_volume(r);
            let v = [p.vx[a], p.vy[a], p.vz[a]];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let f = if a < p.n_mobile { drag(a) } else { [0.0; 3] };
            let fv = f[0] * v[0] + f[1] * v[1] + f[2] * v[2];
            sphere_slices(zc, r, n, slices.dz, |c, w| {
                let share = w / vp;
                self.vyz[c] += w * v[1] * v[2];
                self.vz_v2[c] += w * v[2] * v2;
                self.count[c] += share;
                for (d, fk) in self.drag.iter_mut().zip(f) {
                    d[c] += share * fk;
                }
                self.drag_v[c] += share * fv;
            });
        }
        self.samples += 1;
    }

    /// The time-averaged fields, with the particle moments of `stats` (taken at the same
    /// samples) on slices of volume `cell_volume` = A dz (m^3) and height `dz` (m).
    pub fn averages(&self, stats: &Stats, cell_volume: f64, dz: f64, m: &FieldScales) -> GranularAverages {
        let n = self.len();
        let av = stats.averaged(cell_volume);
        let scale = 1.0 / (self.samples.max(1) as f64 * cell_volume);
        let nan = || vec![f64::NAN; n];
        let mut g = GranularAverages {
            p_p: [nan(), nan(), nan()],
            tau_p: [nan(), nan(), nan()],
            sigma: [nan(), nan(), nan()],
            heat_flux: nan(),
            dissipation: nan(),
            drag_dissipation: nan(),
            drag: [nan(), nan(), nan()],
            gamma_dot: nan(),
            inertial_number: nan(),
            viscous_number: nan(),
            mu_eff: nan(),
            coordination: nan(),
        };
        let held = |c: usize| stats.vol[c] > 0.0;
        for c in (0..n).filter(|&c| held(c)) {
            let row = &self.contact[c * CONTACT_FIELDS..(c + 1) * CONTACT_FIELDS];
            let pc = |k: usize| row[k] * scale;
            let rho_phi = m.rho_p * av.phi[c];
            let kinetic = [rho_phi * av.vv[0][c], rho_phi * av.vv[1][c], rho_phi * av.vv[2][c]];
            let (pk_xz, pc_xz) = (rho_phi * av.vv[3][c], pc(PXZ));
            g.p_p = set3(g.p_p, c, [kinetic[2] + pc(PZZ), kinetic[2], pc(PZZ)]);
            g.tau_p = set3(g.tau_p, c, [-(pk_xz + pc_xz), -pk_xz, -pc_xz]);
            g.sigma = set3(g.sigma, c, [kinetic[0] + pc(PXX), kinetic[1] + pc(PYY), kinetic[2] + pc(PZZ)]);
            // raw moments per unit particle volume, for the third moment
            let w = stats.vol[c];
            let u = [av.v[0][c], av.v[1][c], av.v[2][c]];
            let e_vz_vi = [stats.vv[3][c] / w, self.vyz[c] / w, stats.vv[2][c] / w];
            let e_v2 = (stats.vv[0][c] + stats.vv[1][c] + stats.vv[2][c]) / w;
            let u2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
            let udotvz = u[0] * e_vz_vi[0] + u[1] * e_vz_vi[1] + u[2] * e_vz_vi[2];
            // <v'_z v'_i v'_i> = <v_z v^2> - 2 U_i <v_z v_i> - U_z <v^2> + 2 U_z U^2
            let third = self.vz_v2[c] / w - 2.0 * udotvz - u[2] * e_v2 + 2.0 * u[2] * u2;
            let mean_work = u[0] * pc_xz + u[1] * pc(PYZ) + u[2] * pc(PZZ);
            g.heat_flux[c] = 0.5 * rho_phi * third + pc(HEAT) - mean_work;
            g.dissipation[c] = pc(DISS);
            let fd = [self.drag[0][c] * scale, self.drag[1][c] * scale, self.drag[2][c] * scale];
            g.drag = set3(g.drag, c, fd);
            g.drag_dissipation[c] = self.drag_v[c] * scale - (u[0] * fd[0] + u[1] * fd[1] + u[2] * fd[2]);
            if self.count[c] > 0.0 {
                g.coordination[c] = 2.0 * row[COUNT] / self.count[c];
            }
        }
        for c in 0..n {
            let (lo, hi) = (c.saturating_sub(1), (c + 1).min(n - 1));
            let (lo, hi) = if held(lo) && held(hi) { (lo, hi) } else { (c, c) };
            if hi > lo && held(c) {
                g.gamma_dot[c] = (av.v[0][hi] - av.v[0][lo]) / ((hi - lo) as f64 * dz);
            }
            let (p, t, s) = (g.p_p[0][c], g.tau_p[0][c], g.gamma_dot[c].abs());
            if p > 0.0 {
                g.mu_eff[c] = t / p;
                g.inertial_number[c] = s * m.d / (p / m.rho_p).sqrt();
                g.viscous_number[c] = m.eta_f.map_or(f64::NAN, |eta| eta * s / p);
            }
        }
        g
    }
}

fn set3(mut a: [Vec<f64>; 3], c: usize, v: [f64; 3]) -> [Vec<f64>; 3] {
    for k in 0..3 {
        a[k][c] = v[k];
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lagrangian::engine::slicing::cap_volume;

    /// int over [h0, h1] of (S_a - S_b) / (z_b - z_a) by Simpson's rule on the cap
    /// volumes: an independent evaluation of the shares.
    fn quadrature(a: End, b: End, h0: f64, h1: f64) -> f64 {
        let frac = |e: End, h: f64| cap_volume(e.z, e.r, h) / ball_volume(e.r);
        let g = |h: f64| frac(a, h) - frac(b, h);
        simpson(g, h0, h1, 20_000) / (b.z - a.z)
    }

    /// int over [h0, h1] of g by Simpson's rule on `n` (even) intervals.
    fn simpson(g: impl Fn(f64) -> f64, h0: f64, h1: f64, n: usize) -> f64 {
        let step = (h1 - h0) / n as f64;
        let sum: f64 = (0..=n)
            .map(|k| {
                let w = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * g(h0 + k as f64 * step)
            })
            .sum();
        sum * step / 3.0
    }

    #[test]
    fn a_contact_across_a_slice_face_splits_its_stress_exactly() {
        // two grains of d = 1 mm in contact, branch (0.55, 0, 0.8) mm from z = 1.2 mm,
        // slices of 1 mm: the contact reaches slices 0 to 2, most of it in slices 1 and 2
        // either side of the face at 2 mm. Each slice gets its share w_c of every value,
        // the shares are the integrals of (S_a - S_b) / (z_b - z_a) (checked against
        // quadrature) and add up to 1, so the slices hold the whole contact
        let slices = Slices { base: 0.0, dz: 1e-3, n: 4 };
        let (a, b) = (End { z: 1.2e-3, r: 0.5e-3 }, End { z: 2.0e-3, r: 0.5e-3 });
        let branch = [0.55e-3, 0.0, 0.8e-3];
        let f = [0.3, 0.1, -2.0];
        let vals = contact_values(branch, f, [0.1, 0.0, 0.0], [0.2, 0.0, 0.05], 0.7, 1.0);
        let mut slab = vec![0.0; slices.n * CONTACT_FIELDS];
        spread(&slices, &mut slab, a, b, &vals);
        let mut total = 0.0;
        for c in 0..slices.n {
            let share = quadrature(a, b, c as f64 * 1e-3, (c + 1) as f64 * 1e-3);
            total += share;
            for k in 0..CONTACT_FIELDS {
                let got = slab[c * CONTACT_FIELDS + k];
                assert!((got - share * vals[k]).abs() <= 1e-9 * vals[k].abs(), "slice {c}, field {k}: {got}");
            }
        }
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        let (s1, s2) = (slab[CONTACT_FIELDS + COUNT], slab[2 * CONTACT_FIELDS + COUNT]);
        assert!(s1 + s2 > 0.9 && s2 > 0.05, "{s1} {s2}");
        assert!(slab[3 * CONTACT_FIELDS..].iter().all(|v| *v == 0.0), "nothing above both grains");
        for k in 0..CONTACT_FIELDS {
            let sum: f64 = (0..slices.n).map(|c| slab[c * CONTACT_FIELDS + k]).sum();
            assert!((sum - vals[k]).abs() <= 1e-12 * vals[k].abs(), "field {k}: {sum} vs {}", vals[k]);
        }
        // P_zz integrated over z is -f_z b_z, the force across the slices times the
        // branch's rise; compressive: a force pushing a away from b gives P_zz > 0
        assert!((vals[PZZ] - (-f[2] * branch[2])).abs() < 1e-15 && vals[PZZ] > 0.0);
        assert_eq!([vals[PXZ], vals[PYZ]], [-f[0] * branch[2], -f[1] * branch[2]]);
    }

    #[test]
    fn a_horizontal_branch_and_a_wall_contact_keep_their_whole_share() {
        let s = Slices { base: 1.0, dz: 0.5, n: 2 };
        let mut got = Vec::new();
        // horizontal: the mean of the two grains' volume shares
        s.branch(End { z: 1.5, r: 0.25 }, End { z: 1.5, r: 0.25 }, |c, w, u| got.push((c, w, u)));
        assert_eq!(got.len(), 2);
        assert!(got.iter().all(|g| (g.1 - 0.5).abs() < 1e-12 && g.2 == g.1), "{got:?}");
        got.clear();
        // a grain on a wall at the base: all of the contact is inside the slices
        s.branch(End { z: 1.2, r: 0.2 }, End { z: 1.0, r: 0.0 }, |c, w, u| got.push((c, w, u)));
        assert!((got.iter().map(|g| g.1).sum::<f64>() - 1.0).abs() < 1e-12, "{got:?}");
        assert!((got.iter().map(|g| g.2).sum::<f64>() - 1.0).abs() < 1e-12, "{got:?}");
        assert!(got.iter().all(|g| g.1 >= 0.0 && g.2 >= 0.0));
        got.clear();
        // out of the slices, or not a number: nothing
        s.branch(End { z: 0.2, r: 0.1 }, End { z: 0.5, r: 0.1 }, |c, w, u| got.push((c, w, u)));
        s.branch(End { z: 2.5, r: 0.1 }, End { z: 2.8, r: 0.1 }, |c, w, u| got.push((c, w, u)));
        s.branch(End { z: f64::NAN, r: 0.1 }, End { z: 1.2, r: 0.1 }, |c, w, u| got.push((c, w, u)));
        assert!(got.is_empty(), "{got:?}");
    }

    /// int over [h0, h1] of |S_a - S_b| by Simpson's rule on the cap volumes (the
    /// absolute value makes it converge slowly where S_a - S_b changes sign, hence the
    /// many points).
    fn quadrature_abs(a: End, b: End, h0: f64, h1: f64) -> f64 {
        let frac = |e: End, h: f64| cap_volume(e.z, e.r, h) / ball_volume(e.r);
        let g = |h: f64| (frac(a, h) - frac(b, h)).abs();
        simpson(g, h0, h1, 200_000)
    }

    #[test]
    fn grains_of_two_sizes_on_a_nearly_level_branch_add_no_negative_count() {
        // a bigger grain (r = 0.54 mm) beside a smaller one (0.46 mm) 1 um higher, as a
        // size dispersion of 8 % gives: S_a - S_b is positive below the centres and
        // negative above, and its integral over a slice of 0.1 mm divided by the 1 um rise
        // reaches -4 and +4. The count, P_xx, P_yy and the dissipation take the share
        // |S_a - S_b| / int |S_a - S_b| (checked against quadrature): none negative,
        // adding up to the contact; the fields carrying the rise keep the exact signed
        // split, whose product with the rise is bounded
        let slices = Slices { base: 0.0, dz: 0.1e-3, n: 40 };
        let (a, b) = (End { z: 2.0e-3, r: 0.54e-3 }, End { z: 2.001e-3, r: 0.46e-3 });
        let mut got = Vec::new();
        slices.branch(a, b, |c, w, u| got.push((c, w, u)));
        assert!(got.iter().any(|g| g.1 < -1.0), "the signed share changes sign: {got:?}");
        let total = quadrature_abs(a, b, 1.4e-3, 2.6e-3);
        for &(c, _, u) in &got {
            let h0 = c as f64 * slices.dz;
            let want = quadrature_abs(a, b, h0, h0 + slices.dz) / total;
            assert!(u >= 0.0 && (u - want).abs() < 1e-6, "slice {c}: {u} vs {want}");
        }
        assert!((got.iter().map(|g| g.2).sum::<f64>() - 1.0).abs() < 1e-12);
        assert!((got.iter().map(|g| g.1).sum::<f64>() - 1.0).abs() < 1e-9);
        let branch = [1.0e-3, 0.0, 1.0e-6];
        let vals = contact_values(branch, [-0.5, 0.0, 0.01], [0.1, 0.0, 0.0], [0.2, 0.0, 0.0], 0.3, 1.0);
        let mut slab = vec![0.0; slices.n * CONTACT_FIELDS];
        spread(&slices, &mut slab, a, b, &vals);
        for row in slab.chunks_exact(CONTACT_FIELDS) {
            assert!(row[COUNT] >= 0.0 && row[DISS] >= 0.0 && row[PXX] >= 0.0, "{row:?}");
            // w times the rise is the integral of S_a - S_b over the slice: at most dz
            assert!(row[PZZ].abs() <= 0.01 * slices.dz && row[PXZ].abs() <= 0.5 * slices.dz, "{row:?}");
        }
        for k in 0..CONTACT_FIELDS {
            let sum: f64 = slab.chunks_exact(CONTACT_FIELDS).map(|r| r[k]).sum();
            assert!((sum - vals[k]).abs() <= 1e-9 * vals[k].abs(), "field {k}: {sum} vs {}", vals[k]);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config::with_cases(256))]

        /// Any contact of two grains of radii 0.3 to 0.7, or of a grain and a point inside
        /// it (a wall overlapped), on slices that hold all of it: the share u is never
        /// negative and both shares add up to 1; they are the same share where one grain
        /// does not reach past the other on both sides.
        #[test]
        fn the_shares_of_a_contact_add_up_to_one_and_u_is_never_negative(
            ra in 0.3f64..0.7,
            rb in 0.3f64..0.7,
            point in proptest::bool::ANY,
            t in -1.0f64..1.0,
            za in 2.0f64..3.0,
            dz in 0.02f64..1.0,
        ) {
            let rb = if point { 0.0 } else { rb };
            let b = End { z: za + t * (ra + rb), r: rb };
            let a = End { z: za, r: ra };
            let slices = Slices { base: 0.0, dz, n: (6.0 / dz).ceil() as usize };
            let mut got = Vec::new();
            slices.branch(a, b, |c, w, u| got.push((c, w, u)));
            let (sw, su): (f64, f64) = got.iter().fold((0.0, 0.0), |(x, y), g| (x + g.1, y + g.2));
            proptest::prop_assert!((sw - 1.0).abs() < 1e-9 && (su - 1.0).abs() < 1e-9, "{sw} {su} {got:?}");
            proptest::prop_assert!(got.iter().all(|g| g.2 >= 0.0), "{got:?}");
            if (ra - rb).abs() <= (b.z - a.z).abs() {
                proptest::prop_assert!(got.iter().all(|g| g.1 == g.2), "{got:?}");
            }
        }
    }
}
