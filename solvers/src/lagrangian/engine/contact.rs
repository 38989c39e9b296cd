//! Contact laws between spheres (and between a sphere and a wall).
//!
//! # Linear spring-dashpot with a Coulomb slider (default)
//!
//! Normal force on particle i from j, with n the unit vector from i to j, the overlap
//! delta = R_i + R_j - |x_j - x_i| > 0 and v_n the normal relative velocity (negative when
//! approaching):
//!
//! ```text
//! F_n = -(k_n delta - c_n v_n) n,    c_n = 2 zeta sqrt(k_n m*),
//! zeta = -ln e / sqrt(pi^2 + ln^2 e)
//! ```
//!
//! with m* = m_i m_j / (m_i + m_j) (m_i for a fixed partner or a wall). This is the damped
//! oscillator whose restitution coefficient is exactly e, independent of the impact
//! velocity (Schwager & Poschel 2007, the law of Maurin et al. 2015 section II A and
//! Chassagne et al. 2023 section 2.2). The force is not clipped at zero: the contact ends
//! when the overlap vanishes, which is the definition behind the e(zeta) relation.
//!
//! Tangential force: a spring of stiffness k_t on the accumulated tangential
//! displacement xi of the contact (the contact history), xi projected on the current
//! tangent plane every step and incremented by v_t dt, capped by the Coulomb slider
//! |F_t| <= mu max(|F_n|, 0) (Cundall & Strack 1979; Maurin 2015 section II A,
//! k_s = k_n / 2 there, k_s = k_n in Chassagne 2023 section 2.2). When the slider slips, xi
//! is reset to the capped force over k_t.
//!
//! The option `particles.contact.tangential_history = "rotate"` turns xi with the contact
//! instead of projecting it, as YADE does (`ScGeom::rotate`): xi is carried onto the new
//! tangent plane with its length kept, then rotated about the normal by the angle
//! 0.5 (w_i + w_j) . n dt the pair spins about it (Rodrigues' formula, exact for that
//! angle). Projection shortens xi by cos(theta) per step, theta the angle the normal
//! turned (second order in dt), and leaves xi fixed in space while both grains spin about
//! their common normal, which is not objective; the rotated spring is.
//!
//! Collision time of a pair of equal particles of mass m: t_c = pi sqrt(m / (2 k_n)) /
//! sqrt(1 - zeta^2); the time step is a safety factor times the undamped
//! pi sqrt(m_min / (2 k_n)).
//!
//! # Hertz-Mindlin (option)
//!
//! F_n = (4/3) E* sqrt(R*) delta^{3/2} - 2 sqrt(5/6) beta sqrt(S_n m*) v_n,
//! S_n = 2 E* sqrt(R* delta), beta = ln e / sqrt(ln^2 e + pi^2), tangential stiffness
//! S_t = 8 G* sqrt(R* delta) on the same incremental history and Coulomb cap, with
//! 1/E* = 2 (1 - nu^2)/E, 1/G* = 2 * 2 (2 - nu)(1 + nu)/E for identical materials and
//! R* = R_i R_j / (R_i + R_j) (R_i against a wall). The damping is the usual
//! restitution-matched form (Tsuji et al. 1992; the DEM-code convention), which gives a
//! restitution close to, not exactly, e. Time step: a safety factor times the Rayleigh
//! time pi R sqrt(rho / G) / (0.1631 nu + 0.8766).

pub use saltus_core::scene::{ContactModel, NormalForce, TangentialHistory};

/// Parameters of the contact law, resolved for the run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactLaw {
    /// the law
    pub model: ContactModel,
    /// normal stiffness k_n (N/m), linear law
    pub kn: f64,
    /// tangential stiffness k_t (N/m), linear law
    pub kt: f64,
    /// normal restitution coefficient e in (0, 1]
    pub restitution: f64,
    /// Coulomb friction coefficient mu >= 0
    pub friction: f64,
    /// effective Young modulus E* (Pa), Hertz law
    pub e_star: f64,
    /// effective shear modulus G* (Pa), Hertz law
    pub g_star: f64,
    /// zeta of the linear law (damping ratio)
    pub zeta: f64,
    /// 2 sqrt(5/6) |beta| of the Hertz law
    pub hertz_damping: f64,
    /// the normal force is clipped at zero ([`NormalForce::Repulsive`])
    #[serde(default)]
    pub repulsive: bool,
    /// the tangential spring turns with the contact ([`TangentialHistory::Rotate`])
    #[serde(default)]
    pub rotate_history: bool,
}

impl ContactLaw {
    /// Linear spring-dashpot law.
    pub fn linear(kn: f64, kt: f64, restitution: f64, friction: f64) -> Self {
        let le = restitution.ln();
        let zeta = -le / (std::f64::consts::PI.powi(2) + le * le).sqrt();
        Self {
            model: ContactModel::Linear,
            kn,
            kt,
            restitution,
            friction,
            e_star: 0.0,
            g_star: 0.0,
            zeta,
            hertz_damping: 0.0,
            repulsive: false,
            rotate_history: false,
        }
    }

    /// The law with the normal force `normal`. A repulsive linear law takes the damping
    /// ratio whose clipped force gives the restitution e (Schwager & Poschel 2007, the
    /// underdamped case): the contact ends where k_n delta = c_n v_n, at omega t =
    /// pi - 2 arctan r, so e = exp(-r (pi - 2 arctan r)) with r = beta / omega =
    /// zeta / sqrt(1 - zeta^2), increasing in r from e = 1 at r = 0 to e^-2 as r -> inf
    /// (critical damping). Solved for r by bisection on ln e; e <= e^-2 (refused at scene
    /// load) gives critical damping. The Hertz law keeps its damping (its e is approximate
    /// either way).
    pub fn with_normal_force(mut self, normal: NormalForce) -> Self {
        self.repulsive = normal == NormalForce::Repulsive;
        if self.repulsive && self.model == ContactModel::Linear {
            let target = -self.restitution.ln();
            let loss = |r: f64| r * (std::f64::consts::PI - 2.0 * r.atan());
            let (mut lo, mut hi) = (0.0f64, 1e12f64);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if loss(mid) < target {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let r = 0.5 * (lo + hi);
            self.zeta = r / (1.0 + r * r).sqrt();
        }
        self
    }

    /// The law with the tangential spring's update `history`.
    pub fn with_tangential_history(mut self, history: TangentialHistory) -> Self {
        self.rotate_history = history == TangentialHistory::Rotate;
        self
    }

    /// Hertz-Mindlin law for identical spheres of Young modulus `young` (Pa) and Poisson
    /// ratio `poisson`.
    pub fn hertz(young: f64, poisson: f64, restitution: f64, friction: f64) -> Self {
        let le = restitution.ln();
        let beta = le / (le * le + std::f64::consts::PI.powi(2)).sqrt();
        let shear = young / (2.0 * (1.0 + poisson));
        Self {
            model: ContactModel::Hertz,
            kn: 0.0,
            kt: 0.0,
            restitution,
            friction,
            e_star: young / (2.0 * (1.0 - poisson * poisson)),
            g_star: shear / (2.0 * (2.0 - poisson)),
            zeta: 0.0,
            hertz_damping: 2.0 * (5.0f64 / 6.0).sqrt() * beta.abs(),
            repulsive: false,
            rotate_history: false,
        }
    }

    /// Damping factor per sqrt(m*) of the linear law: c_n = factor sqrt(m*).
    pub fn damping_factor(&self) -> f64 {
        2.0 * self.zeta * self.kn.sqrt()
    }

    /// Time scale of a contact between two particles of mass `m`, radius `r`, density
    /// `rho` and, for Hertz, shear modulus from `young`/`poisson` (s): pi sqrt(m / (2 k_n))
    /// for the linear law, the Rayleigh time for Hertz.
    pub fn contact_time(&self, m: f64, r: f64, rho: f64, young: f64, poisson: f64) -> f64 {
        match self.model {
            ContactModel::Linear => std::f64::consts::PI * (m / (2.0 * self.kn)).sqrt(),
            ContactModel::Hertz => {
                let shear = young / (2.0 * (1.0 + poisson));
                std::f64::consts::PI * r * (rho / shear).sqrt() / (0.1631 * poisson + 0.8766)
            }
        }
    }
}

/// Geometry and kinematics of one contact, from the point of view of particle i.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactInput {
    /// unit normal from i to j
    pub n: [f64; 3],
    /// overlap (m), > 0
    pub delta: f64,
    /// velocity of j's contact point relative to i's (m/s)
    pub v_rel: [f64; 3],
    /// sqrt of the effective mass (sqrt kg)
    pub sqrt_m: f64,
    /// effective radius R* (m), Hertz only
    pub r_eff: f64,
    /// mean spin of the pair about n, 0.5 (w_i + w_j) . n (rad/s; the wall's and
    /// cylinder's w is zero); read only by the rotated tangential spring
    pub spin_n: f64,
}

/// Force on particle i (N), with the updated tangential history `h` (m), and the power
/// the contact dissipates over the step (W, >= 0; the function is inlined, so a caller
/// that drops it does not compute it): the dashpot's c v_n^2 (c = c_n sqrt(m*) of the
/// linear law, 2 sqrt(5/6) |beta| sqrt(S_n m*) of Hertz) plus, when the Coulomb slider
/// slips, cap |Delta xi| / dt with |Delta xi| = (|F_t,trial| - cap) / k_t the spring
/// displacement the slip removes (the work of a force of magnitude cap against that
/// slip). The springs store energy and give it back: they are not in it.
#[inline(always)]
pub(crate) fn contact_force(law: &ContactLaw, c: &ContactInput, h: &mut [f64; 3], dt: f64) -> ([f64; 3], f64) {
    let n = c.n;
    let vn = c.v_rel[0] * n[0] + c.v_rel[1] * n[1] + c.v_rel[2] * n[2];
    let (fn_, kt, damping) = match law.model {
        ContactModel::Linear => {
            let damping = law.damping_factor() * c.sqrt_m;
            (law.kn * c.delta - damping * vn, law.kt, damping)
        }
        ContactModel::Hertz => {
            let a = (c.r_eff * c.delta).sqrt();
            let sn = 2.0 * law.e_star * a;
            let elastic = 4.0 / 3.0 * law.e_star * a * c.delta;
            let damping = law.hertz_damping * (sn).sqrt() * c.sqrt_m;
            (elastic - damping * vn, 8.0 * law.g_star * a, damping)
        }
    };
    // a repulsive law ends the contact's pull: no force, no dashpot work
    let (fn_, mut power) = if law.repulsive && fn_ < 0.0 { (0.0, 0.0) } else { (fn_, damping * vn * vn) };
    let vt = [c.v_rel[0] - vn * n[0], c.v_rel[1] - vn * n[1], c.v_rel[2] - vn * n[2]];
    if law.rotate_history {
        rotate_history(h, n, c.spin_n * dt);
        for k in 0..3 {
            h[k] += vt[k] * dt;
        }
    } else {
        // keep the spring in the tangent plane as the contact rolls
        let hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
        for k in 0..3 {
            h[k] += vt[k] * dt - hn * n[k];
        }
    }
    let mut ft = [kt * h[0], kt * h[1], kt * h[2]];
    let ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
    let cap = law.friction * fn_.max(0.0);
    if ft2 > cap * cap {
        let s = if ft2 > 0.0 { cap / ft2.sqrt() } else { 0.0 };
        for k in 0..3 {
            ft[k] *= s;
            h[k] *= s;
        }
        if kt > 0.0 {
            power += cap * (ft2.sqrt() - cap) / (kt * dt);
        }
    }
    ([-fn_ * n[0] + ft[0], -fn_ * n[1] + ft[1], -fn_ * n[2] + ft[2]], power)
}

/// Turn the spring `h` with its contact: onto the tangent plane of `n` with its length
/// kept, then by `angle` (rad) about `n`.
#[inline(always)]
fn rotate_history(h: &mut [f64; 3], n: [f64; 3], angle: f64) {
    let len2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    let hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
    let mut p = [h[0] - hn * n[0], h[1] - hn * n[1], h[2] - hn * n[2]];
    let p2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    // a spring along the new normal has no direction in the plane to keep: it is dropped
    let scale = if p2 > 0.0 { (len2 / p2).sqrt() } else { 0.0 };
    // Rodrigues about n, p being normal to it: p cos a + (n x p) sin a
    let (s, c) = angle.sin_cos();
    let q = cross(n, p);
    for k in 0..3 {
        p[k] = scale * (p[k] * c + q[k] * s);
    }
    *h = p;
}

#[inline(always)]
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn damping_ratio_limits(e in 1e-3f64..=1.0) {
            // zeta decreases from ~1 (e -> 0) to 0 (e = 1): underdamped for every e > 0
            let law = ContactLaw::linear(1e4, 1e4, e, 0.4);
            prop_assert!(law.zeta >= 0.0 && law.zeta < 1.0);
            // closed form of the damped oscillator: e = exp(-pi zeta / sqrt(1 - zeta^2))
            let back = (-std::f64::consts::PI * law.zeta / (1.0 - law.zeta * law.zeta).sqrt()).exp();
            prop_assert!((back / e - 1.0).abs() < 1e-12);
        }

        #[test]
        fn repulsive_damping_gives_e_by_its_own_relation(e in 0.1354f64..=1.0) {
            // Schwager & Poschel 2007: e = exp(-r (pi - 2 arctan r)), r = zeta / sqrt(1 - zeta^2);
            // more damping than the spring-dashpot's for the same e (its pull is gone)
            let sd = ContactLaw::linear(1e4, 1e4, e, 0.4);
            let law = sd.with_normal_force(NormalForce::Repulsive);
            let r = law.zeta / (1.0 - law.zeta * law.zeta).sqrt();
            let back = (-r * (std::f64::consts::PI - 2.0 * r.atan())).exp();
            prop_assert!((back / e - 1.0).abs() < 1e-10, "{back} vs {e}");
            prop_assert!(law.zeta >= sd.zeta && law.zeta < 1.0 && law.repulsive);
            // the spring-dashpot is untouched
            prop_assert_eq!(sd.with_normal_force(NormalForce::SpringDashpot), sd);
        }

        #[test]
        fn a_repulsive_contact_never_pulls(delta in 1e-9f64..1e-4, vn in -10.0f64..10.0) {
            let law = ContactLaw::linear(1e4, 1e4, 0.7, 0.4).with_normal_force(NormalForce::Repulsive);
            let c = ContactInput { n: [0.0, 0.0, 1.0], delta, v_rel: [0.0, 0.0, vn], sqrt_m: 0.01, r_eff: 0.003, spin_n: 0.0 };
            let (f, power) = contact_force(&law, &c, &mut [0.0; 3], 1e-4);
            // force on i along -n: repulsion pushes i away from j (f_z <= 0), never towards it
            prop_assert!(f[2] <= 0.0 && power >= 0.0);
            let pulls = law.kn * delta - law.damping_factor() * 0.01 * vn < 0.0;
            prop_assert!(!pulls || (f[2] == 0.0 && power == 0.0));
        }

        #[test]
        fn coulomb_cap_holds(delta in 1e-9f64..1e-4, vt in -10.0f64..10.0, mu in 0.0f64..2.0) {
            let law = ContactLaw::linear(1e4, 1e4, 0.7, mu);
            let c = ContactInput { n: [0.0, 0.0, 1.0], delta, v_rel: [vt, 0.0, 0.0], sqrt_m: 0.01, r_eff: 0.003, spin_n: 0.0 };
            let mut h = [0.0; 3];
            let f = contact_force(&law, &c, &mut h, 1e-4).0;
            let fn_ = -f[2];
            prop_assert!(f[0].abs() <= mu * fn_.max(0.0) * (1.0 + 1e-12) + 1e-300);
            // the spring always holds the force it transmits
            prop_assert!((law.kt * h[0] - f[0]).abs() <= 1e-12 * f[0].abs().max(1e-300));
        }
    }

    #[test]
    fn hertz_elastic_force() {
        // F = (4/3) E* sqrt(R*) delta^{3/2} at zero normal velocity
        let law = ContactLaw::hertz(1e7, 0.3, 0.7, 0.4);
        let c =
            ContactInput { n: [0.0, 0.0, 1.0], delta: 1e-6, v_rel: [0.0; 3], sqrt_m: 0.01, r_eff: 1.5e-3, spin_n: 0.0 };
        let f = contact_force(&law, &c, &mut [0.0; 3], 1e-6).0;
        let e_star = 1e7 / (2.0 * (1.0 - 0.09));
        let expected = 4.0 / 3.0 * e_star * (1.5e-3f64).sqrt() * 1e-9;
        assert!((-f[2] / expected - 1.0).abs() < 1e-12);
    }

    /// A loaded spring of a pair that spins rigidly about its normal (both grains at w
    /// along n, no relative motion of the contact points): the rotated spring turns with
    /// the grains, by w t exactly, and keeps its length; the projected one stays put.
    #[test]
    fn a_rotated_spring_turns_with_a_pair_spinning_about_its_normal() {
        let (w, dt, steps) = (50.0, 1e-5, 2000);
        let h0 = [1e-6, 0.0, 0.0];
        for rotate in [false, true] {
            let history = if rotate { TangentialHistory::Rotate } else { TangentialHistory::Project };
            let law = ContactLaw::linear(1e4, 1e4, 0.7, 1e6).with_tangential_history(history);
            let c = ContactInput {
                n: [0.0, 0.0, 1.0],
                delta: 1e-4,
                v_rel: [0.0; 3],
                sqrt_m: 0.01,
                r_eff: 0.003,
                spin_n: w,
            };
            let mut h = h0;
            let mut f = [0.0; 3];
            for _ in 0..steps {
                f = contact_force(&law, &c, &mut h, dt).0;
            }
            let angle: f64 = w * dt * steps as f64;
            let expected = if rotate { [1e-6 * angle.cos(), 1e-6 * angle.sin(), 0.0] } else { h0 };
            for k in 0..3 {
                assert!((h[k] - expected[k]).abs() < 1e-15, "rotate {rotate}: {h:?} against {expected:?}");
            }
            // the tangential force is the spring's
            for k in 0..2 {
                assert!((f[k] - law.kt * h[k]).abs() < 1e-12);
            }
        }
    }

    /// A pair whose normal turns a quarter turn about an axis in the tangent plane, the
    /// contact points moving with it (v_rel = 0): the exact spring turns rigidly with
    /// the normal. The rotated spring keeps its length to rounding and its direction to
    /// first order in the step; the projected one loses, per step, the factor cos of the
    /// step's angle on its component along the turn.
    #[test]
    fn a_rotated_spring_keeps_its_length_as_the_normal_turns() {
        let quarter = std::f64::consts::FRAC_PI_2;
        // h0 normal to n0 = z: one part along the rotation axis y, one along x
        let h0: [f64; 3] = [1e-6, 2e-6, 0.0];
        let len0 = (h0[0] * h0[0] + h0[1] * h0[1]).sqrt();
        let mut errors = Vec::new();
        for steps in [500usize, 2000] {
            let step = quarter / steps as f64;
            for rotate in [false, true] {
                let history = if rotate { TangentialHistory::Rotate } else { TangentialHistory::Project };
                let law = ContactLaw::linear(1e4, 1e4, 0.7, 1e6).with_tangential_history(history);
                let mut h = h0;
                for s in 1..=steps {
                    let t = step * s as f64;
                    let n = [t.sin(), 0.0, t.cos()];
                    let c = ContactInput { n, delta: 1e-4, v_rel: [0.0; 3], sqrt_m: 0.01, r_eff: 0.003, spin_n: 0.0 };
                    contact_force(&law, &c, &mut h, 1e-5);
                }
                // rigid quarter turn about y: x -> -z, y stays
                let exact = [0.0, h0[1], -h0[0]];
                let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
                let err = ((h[0] - exact[0]).powi(2) + (h[1] - exact[1]).powi(2) + (h[2] - exact[2]).powi(2)).sqrt();
                if rotate {
                    assert!((len / len0 - 1.0).abs() < 1e-12, "{len} against {len0}");
                } else {
                    // the x part shrinks by cos(step)^steps
                    let kept = step.cos().powi(steps as i32);
                    let expected = (h0[0] * h0[0] * kept * kept + h0[1] * h0[1]).sqrt();
                    assert!((len / expected - 1.0).abs() < 1e-9, "{len} against {expected}");
                    assert!(len < len0);
                }
                errors.push((steps, rotate, err / len0));
            }
        }
        // both converge to the rigid turn at first order: 4x the steps, about 4x less error
        for rotate in [false, true] {
            let e: Vec<f64> = errors.iter().filter(|e| e.1 == rotate).map(|e| e.2).collect();
            let ratio = e[0] / e[1];
            assert!(e[0] < 1e-2 && (3.0..5.0).contains(&ratio), "rotate {rotate}: errors {e:?}");
        }
    }
}
