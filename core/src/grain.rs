//! Properties of one spherical grain and of a random packing of them that every side of
//! the library uses: the closures (the radial distribution of kinetic theory), the scene
//! (particle counts from a packing), the solvers (masses, volume fractions, the Haff
//! cooling time) and the diagnostics. One definition each, so that a DEM count, a
//! continuum coefficient and a comparison of the two evaluate the same expression.

/// Volume of a sphere of diameter `d`, pi d^3 / 6 (m^3 for `d` in m), evaluated as
/// `PI * d * d * d / 6`.
#[inline]
pub const fn sphere_volume(d: f64) -> f64 {
    std::f64::consts::PI * d * d * d / 6.0
}

/// Volume of a sphere of radius `r`, 4/3 pi r^3, evaluated as `4 / 3 * PI * r * r * r`: the
/// form the DEM weighs its particles' slices by ([`sphere_volume`] of the diameter rounds
/// differently in the last bit).
#[inline]
pub const fn ball_volume(r: f64) -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * r * r * r
}

/// Carnahan & Starling (1969) radial distribution at contact of hard spheres,
/// g0 = (2 - phi) / (2 (1 - phi)^3).
///
/// * Source: Carnahan & Starling 1969; Chassagne et al. 2023, text before eq 2.23, where
///   it is the dilute part of the Chialvo-Sundaresan forms (eqs 2.23, 3.2).
/// * g0(0) = 1; finite for phi < 1, `+inf` for phi >= 1 (its own divergence: it ignores
///   a maximum packing, which is why the papers replace it in dense flows).
/// * Valid range: phi in [0, 1); it is a fit of the hard-sphere fluid, accurate to about
///   1 % up to phi ~ 0.5.
#[inline]
pub fn carnahan_starling(phi: f64) -> f64 {
    if phi >= 1.0 {
        return f64::INFINITY;
    }
    let q = 1.0 - phi;
    (2.0 - phi) / (2.0 * q * q * q)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_sphere_and_a_scaled_one() {
        assert_eq!(sphere_volume(1.0), std::f64::consts::PI / 6.0);
        // volume scales as d^3, and a sphere of radius r is 4/3 pi r^3
        let r = 3e-3;
        let v = sphere_volume(2.0 * r);
        assert!((v / (4.0 / 3.0 * std::f64::consts::PI * r * r * r) - 1.0).abs() < 1e-15, "{v}");
        assert!((sphere_volume(2.0) / sphere_volume(1.0) - 8.0).abs() < 1e-14);
    }

    #[test]
    fn carnahan_starling_limits_and_virial_expansion() {
        assert_eq!(carnahan_starling(0.0), 1.0);
        assert_eq!(carnahan_starling(1.0), f64::INFINITY);
        assert_eq!(carnahan_starling(1.5), f64::INFINITY);
        // the exact virial series of hard spheres starts g0 = 1 + 5/2 phi + 4.5904 phi^2,
        // and Carnahan-Starling's 1 + 5/2 phi + 9/2 phi^2 + ... matches its first two
        // terms: at phi = 1e-4 the difference from 1 + 5/2 phi is 9/2 phi^2 to 1e-3
        let phi = 1e-4;
        let rest = (carnahan_starling(phi) - 1.0 - 2.5 * phi) / (phi * phi);
        assert!((rest - 4.5).abs() < 1e-2, "{rest}");
        // at phi = 0.5: 1.5 / (2 x 0.125) = 6
        assert!((carnahan_starling(0.5) - 6.0).abs() < 1e-15);
    }
}
