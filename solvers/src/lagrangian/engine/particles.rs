//! Particle state as a structure of arrays, and the periodic box it lives in.

/// The simulation box: periodic in the directions flagged in `periodic`, bounded by walls
/// or open otherwise.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Box3 {
    /// extent (m) in x, y, z; only meaningful along periodic directions (the period)
    pub length: [f64; 3],
    /// periodic directions
    pub periodic: [bool; 3],
}

impl Box3 {
    /// Shift that brings `d` (a coordinate difference) to its minimum image along `axis`.
    #[inline]
    pub fn image_shift(&self, axis: usize, d: f64) -> f64 {
        if self.periodic[axis] {
            let l = self.length[axis];
            -l * (d / l).round()
        } else {
            0.0
        }
    }
}

/// A particle's position and radius side by side, one aligned half cache line: the
/// overlap tests of the pair loop and of the neighbour build read two of them at random,
/// instead of four numbers from four arrays (four cache lines per particle).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
pub struct Place(pub [f64; 4]);

/// Spheres as a structure of arrays. Indices `0..n_mobile` are mobile particles,
/// `n_mobile..len()` fixed ones (the rough bottom): fixed particles have zero inverse
/// mass and inertia and are never integrated.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Particles {
    /// number of mobile particles (they come first)
    pub n_mobile: usize,
    /// positions (m); between neighbour-list builds they are not wrapped into the box
    pub x: Vec<f64>,
    /// positions y (m)
    pub y: Vec<f64>,
    /// positions z (m), bed-normal
    pub z: Vec<f64>,
    /// velocities (m/s), at the half step of the leapfrog scheme
    pub vx: Vec<f64>,
    /// velocity y (m/s)
    pub vy: Vec<f64>,
    /// velocity z (m/s)
    pub vz: Vec<f64>,
    /// angular velocities (rad/s)
    pub wx: Vec<f64>,
    /// angular velocity y (rad/s)
    pub wy: Vec<f64>,
    /// angular velocity z (rad/s)
    pub wz: Vec<f64>,
    /// radii (m)
    pub radius: Vec<f64>,
    /// 1 / mass (1/kg), 0 for fixed particles
    pub inv_mass: Vec<f64>,
    /// 1 / moment of inertia (1/(kg m^2)), 0 for fixed particles
    pub inv_inertia: Vec<f64>,
}

impl Particles {
    /// Number of particles, mobile and fixed.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether there is no particle.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The positions and radii of every particle as records (the same numbers), into
    /// `out` (reused).
    pub fn places(&self, out: &mut Vec<Place>) {
        out.clear();
        let pos = self.x.iter().zip(&self.y).zip(&self.z).zip(&self.radius);
        out.extend(pos.map(|(((&x, &y), &z), &radius)| Place([x, y, z, radius])));
    }

    /// Add one sphere of radius `r` and density `rho` at `pos` with velocity `v` and
    /// angular velocity `w`. Mobile particles must all be added before fixed ones.
    pub fn push(&mut self, pos: [f64; 3], v: [f64; 3], w: [f64; 3], r: f64, rho: f64, fixed: bool) {
        let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        self.x.push(pos[0]);
        self.y.push(pos[1]);
        self.z.push(pos[2]);
        self.vx.push(v[0]);
        self.vy.push(v[1]);
        self.vz.push(v[2]);
        self.wx.push(w[0]);
        self.wy.push(w[1]);
        self.wz.push(w[2]);
        self.radius.push(r);
        if fixed {
            self.inv_mass.push(0.0);
            self.inv_inertia.push(0.0);
        } else {
            debug_assert_eq!(self.n_mobile, self.len() - 1, "mobile particles come first");
            self.inv_mass.push(1.0 / m);
            self.inv_inertia.push(1.0 / (0.4 * m * r * r));
            self.n_mobile += 1;
        }
    }

    /// Translational kinetic energy of the mobile particles, sum m v^2 / 2 (J), in
    /// index order.
    pub fn translational_energy(&self) -> f64 {
        (0..self.n_mobile)
            .map(|i| 0.5 * (self.vx[i].powi(2) + self.vy[i].powi(2) + self.vz[i].powi(2)) / self.inv_mass[i])
            .sum()
    }

    /// Rotational kinetic energy of the mobile particles, sum I w^2 / 2 (J).
    pub fn rotational_energy(&self) -> f64 {
        (0..self.n_mobile)
            .map(|i| 0.5 * (self.wx[i].powi(2) + self.wy[i].powi(2) + self.wz[i].powi(2)) / self.inv_inertia[i])
            .sum()
    }

    /// Granular temperature of the mobile particles, `<|v - <v>|^2> / 3` (m^2/s^2).
    pub fn temperature(&self) -> f64 {
        let n = self.n_mobile as f64;
        if self.n_mobile == 0 {
            return 0.0;
        }
        let m = |v: &[f64]| v[..self.n_mobile].iter().sum::<f64>() / n;
        let (mx, my, mz) = (m(&self.vx), m(&self.vy), m(&self.vz));
        let s: f64 = (0..self.n_mobile)
            .map(|i| (self.vx[i] - mx).powi(2) + (self.vy[i] - my).powi(2) + (self.vz[i] - mz).powi(2))
            .sum();
        s / (3.0 * n)
    }
}
