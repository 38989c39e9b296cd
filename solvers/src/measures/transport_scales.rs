//! The scales of the dimensionless transport numbers of a summary.

use saltus_core::scene::Scene;

/// Scales that turn a run's transport and stresses into the dimensionless numbers of the
/// summary, the same for every solver: qs* = qs / sqrt((s-1) g d^3), Shields = tau /
/// ((rho_p - rho_f) g d), nominal Shields = rho_f g sin h_w / ((rho_p - rho_f) g cos d).
#[derive(Clone, Copy, Debug)]
pub struct TransportScales {
    /// sqrt(|s - 1| g d^3) (m^2/s)
    pub qs: f64,
    /// |rho_p - rho_f| g d (Pa)
    pub stress: f64,
    /// Shields number of the driving over the water depth, when the slope drives the flow
    pub shields_nominal: Option<f64>,
}

impl TransportScales {
    /// Scales of `scene` with particles of density `rho_p`, diameter `d` under a water
    /// depth `water_depth`.
    pub fn new(scene: &Scene, rho_p: f64, d: f64, water_depth: f64) -> Self {
        let g = scene.physics.gravity;
        let rho_f = scene.fluid.density;
        let sm1 = rho_p / rho_f - 1.0;
        let stress = (rho_p - rho_f).abs() * g * d;
        let slope = scene.physics.slope;
        let cos = (1.0 - slope * slope).max(0.0).sqrt();
        // undefined (absent) without a stress scale: no gravity or no density contrast
        let shields_nominal = (slope > 0.0 && water_depth > 0.0 && sm1 > 0.0)
            .then(|| rho_f * g * slope * water_depth / (stress * cos))
            .filter(|s| s.is_finite());
        Self { qs: (sm1.abs() * g * d * d * d).sqrt(), stress, shields_nominal }
    }

    /// sqrt(|s - 1| g d) (m/s), the velocity scale of a local flux phi u_p: qs over d.
    pub fn flux_velocity(&self, d: f64) -> f64 {
        self.qs / d
    }

    /// qs* of a transport rate qs (m^2/s); NaN without a scale.
    pub fn qs_star(&self, qs: f64) -> f64 {
        if self.qs > 0.0 {
            qs / self.qs
        } else {
            f64::NAN
        }
    }

    /// Shields number of a shear stress (Pa); NaN without a scale.
    pub fn shields(&self, tau: f64) -> f64 {
        if self.stress > 0.0 {
            tau / self.stress
        } else {
            f64::NAN
        }
    }
}
