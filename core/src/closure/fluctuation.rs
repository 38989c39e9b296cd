//! Fluid velocity fluctuations seen by particles: a stochastic face (one draw per particle
//! per eddy) and a mean-field face (the particle diffusivity the model implies, used for
//! the Eulerian drift velocity u_d = D grad(phi) / phi, Chassagne 2023 eqs 4.3-4.4).

use crate::needs::Needs;
use crate::param::Describe;
use crate::rng::Rng;

/// Local turbulence state at a particle or a cell. Fields a closure does not need may be
/// zero; the scene check guarantees the needed ones are computed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TurbulencePoint {
    /// turbulent kinetic energy k (m^2/s^2)
    pub k: f64,
    /// specific dissipation rate omega (1/s)
    pub omega: f64,
    /// eddy viscosity nu_t (m^2/s)
    pub nu_t: f64,
    /// kinematic Reynolds shear stress magnitude R_xz / (rho_f (1-phi)) (m^2/s^2)
    pub reynolds_stress: f64,
}

/// Column-scale quantities (for the eddy turnover time of the DRW).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FlowScales {
    /// water depth above the bed (m)
    pub depth: f64,
    /// depth-averaged fluid velocity (m/s)
    pub bulk_velocity: f64,
}

/// Particle kinematics relevant to eddy crossing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ParticleSlip {
    /// |v_p - u_f| (m/s)
    pub slip: f64,
    /// particle response time t_p = 4 rho_p d / (3 rho_f C_D |v_p - u_f|) (s)
    pub response_time: f64,
}

/// One stochastic draw: the fluctuation (x, y, z) and how long it holds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FluctuationDraw {
    /// fluid velocity fluctuation (m/s), streamwise x, spanwise y, wall-normal z
    pub u: [f64; 3],
    /// time until the next draw (s); `f64::INFINITY` when no fluctuation is modelled
    pub duration: f64,
}

/// How the mean-field face turns the particle diffusivity D into a wall-normal flux.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriftForm {
    /// gradient diffusion, flux -D dphi/dz: the drift velocity u_d = D grad(phi)/phi of
    /// Chassagne et al. 2023 eq 4.4 (Cheng et al. eq 40)
    Gradient,
    /// flux -d(D phi)/dz: the diffusion limit of a random walk whose velocity and duration
    /// are fixed where each eddy is drawn, u_d = D grad(phi)/phi + grad(D). Such walks
    /// drift towards weak turbulence by grad(D) (MacInnes & Bracco 1992, Phys. Fluids A 4,
    /// 2809: random-walk models violate the well-mixed condition); this form is that of
    /// the draws, so that both faces of one closure give the same profile.
    Ito,
}

/// Which slip the particle Reynolds number of the drag takes when the fluid a grain sees
/// carries a fluctuation u' (the relative velocity u_r = u_f + u' - v).
///
/// * `Instantaneous`: Re_p = |u_f + u' - v| d / nu_f, the slip of the force itself.
/// * `Mean`: Re_p = |u_f - v| d / nu_f, the Reynolds-averaged fluid velocity, as Cheng,
///   Chauchat, Hsu & Calantoni's eq 7 writes it (Re_p = (1 - phi) |u_f - v| d / nu_f, the
///   overbar the Reynolds average; the force of eq 6 keeps the instantaneous slip,
///   F = (1/2) C_D(Re_p) A |u_r| u_r). The hindrance's Re_p is the same one.
///
/// With u' = 0 both are the same number.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SlipReynolds {
    /// the instantaneous slip |u_f + u' - v|
    #[default]
    Instantaneous,
    /// the mean slip |u_f - v| (Cheng eq 7)
    Mean,
}

impl SlipReynolds {
    /// The slip speed of Re_p for the relative velocity `ur` = u_f + u' - v of a grain
    /// whose fluctuation is `fluct` = u' (m/s).
    #[inline]
    pub fn slip(self, ur: [f64; 3], fluct: [f64; 3]) -> f64 {
        let u = match self {
            SlipReynolds::Instantaneous => ur,
            SlipReynolds::Mean => [ur[0] - fluct[0], ur[1] - fluct[1], ur[2] - fluct[2]],
        };
        (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt()
    }
}

/// A fluctuation closure.
#[typetag::serde(tag = "type")]
pub trait Fluctuation: Describe + Send + Sync + std::fmt::Debug {
    /// Fields the closure needs from the turbulence closure.
    fn needs(&self) -> Needs;

    /// Whether the closure draws anything; a scene with an inactive closure pays for no
    /// random numbers and no drift velocity.
    fn is_active(&self) -> bool {
        true
    }

    /// Draw the fluctuation seen by one particle, using the caller's seeded stream.
    fn draw(&self, t: &TurbulencePoint, p: &ParticleSlip, s: &FlowScales, rng: &mut Rng) -> FluctuationDraw;

    /// The form of the mean-field flux; gradient diffusion unless the model says otherwise.
    fn drift_form(&self) -> DriftForm {
        DriftForm::Gradient
    }

    /// Wall-normal particle diffusivity implied by the model (m^2/s).
    fn diffusivity(&self, t: &TurbulencePoint, s: &FlowScales) -> f64;

    /// `Some(phi_b)`: a particle whose centre lies at or below the bed elevation when it
    /// draws sees no fluctuation until its next draw, the bed elevation being the top of
    /// the highest peak of the solid fraction above phi_b (the DEM's
    /// `inputs::peak_bed_elevation`). `None` (the default): the draws apply everywhere.
    /// Acts on the particles' draws only, not on the mean-field face.
    fn above_bed(&self) -> Option<f64> {
        None
    }

    /// The slip of the drag's particle Reynolds number under this closure's draws
    /// ([`SlipReynolds`]); the instantaneous one unless the model says otherwise.
    fn drag_reynolds(&self) -> SlipReynolds {
        SlipReynolds::Instantaneous
    }

    /// Draws for a chunk of particles: draw `j` at `t[j]`, `p[j]` from the stream
    /// `rng[j]` of its particle, into `out[j]`. Each draw takes the numbers of its own
    /// stream in the order [`Fluctuation::draw`] takes them, so the draws are those of one
    /// call per particle whatever the chunking and the thread count. The default calls
    /// [`Fluctuation::draw`] per particle; a model whose law is evaluated on arrays (a
    /// closure written in Python) overrides it with one evaluation per chunk.
    fn draw_batch(
        &self,
        t: &[TurbulencePoint],
        p: &[ParticleSlip],
        s: &FlowScales,
        rng: &mut [&mut Rng],
        out: &mut [FluctuationDraw],
    ) {
        for (((o, t), p), r) in out.iter_mut().zip(t).zip(p).zip(rng.iter_mut()) {
            *o = self.draw(t, p, s, r);
        }
    }

    /// Diffusivity over a column.
    fn diffusivity_batch(&self, t: &[TurbulencePoint], s: &FlowScales, out: &mut [f64]) {
        for (o, tp) in out.iter_mut().zip(t) {
            *o = self.diffusivity(tp, s);
        }
    }
}
