//! Particle snapshots in the legacy VTK format (ParaView opens them; render the points
//! with the `radius` array as sphere glyphs).

use std::fmt::Write as _;

use super::particles::Particles;

/// Legacy ASCII VTK polydata of every particle: points, radius, velocity, angular
/// velocity and a `fixed` flag.
pub fn legacy(p: &Particles) -> String {
    let n = p.len();
    let mut s = String::with_capacity(n * 160 + 256);
    s.push_str("# vtk DataFile Version 3.0\nsaltus DEM particles\nASCII\nDATASET POLYDATA\n");
    let _ = writeln!(s, "POINTS {n} double");
    for k in 0..n {
        let _ = writeln!(s, "{:.9e} {:.9e} {:.9e}", p.x[k], p.y[k], p.z[k]);
    }
    let _ = writeln!(s, "VERTICES {n} {}", 2 * n);
    for k in 0..n {
        let _ = writeln!(s, "1 {k}");
    }
    let _ = writeln!(s, "POINT_DATA {n}\nSCALARS radius double 1\nLOOKUP_TABLE default");
    for k in 0..n {
        let _ = writeln!(s, "{:.9e}", p.radius[k]);
    }
    let _ = writeln!(s, "SCALARS fixed int 1\nLOOKUP_TABLE default");
    for k in 0..n {
        let _ = writeln!(s, "{}", u8::from(k >= p.n_mobile));
    }
    let _ = writeln!(s, "VECTORS velocity double");
    for k in 0..n {
        let _ = writeln!(s, "{:.9e} {:.9e} {:.9e}", p.vx[k], p.vy[k], p.vz[k]);
    }
    let _ = writeln!(s, "VECTORS angular_velocity double");
    for k in 0..n {
        let _ = writeln!(s, "{:.9e} {:.9e} {:.9e}", p.wx[k], p.wy[k], p.wz[k]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_and_counts() {
        let mut p = Particles::default();
        p.push([0.0, 1.0, 2.0], [0.5, 0.0, 0.0], [0.0; 3], 0.003, 2500.0, false);
        p.push([1.0, 1.0, 0.0], [0.0; 3], [0.0; 3], 0.003, 2500.0, true);
        let s = legacy(&p);
        assert!(s.starts_with("# vtk DataFile Version 3.0"));
        assert!(s.contains("POINTS 2 double") && s.contains("VERTICES 2 4") && s.contains("POINT_DATA 2"));
        assert_eq!(s.lines().filter(|l| *l == "1 1").count(), 1);
    }
}
