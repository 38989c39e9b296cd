//! The DEM step with the adapted skin against a brute-force pair search.

use super::*;
use crate::lagrangian::engine::neighbours::{pairs_within, MAX_SKIN_DIAMETERS};

#[test]
fn with_the_adapted_skin_every_contact_gets_its_force() {
    // a dense, fast granular gas (4 m/s against 6 mm grains, 0.22 contact times per
    // step): the skin widens from 0.01 d; after every step, unless the list is due
    // for a rebuild, every pair in contact (brute force over all pairs and images)
    // is listed, so the next step computes its force
    let (l, r) = (0.06, 3e-3);
    let bx = Box3 { length: [l, l, l], periodic: [true; 3] };
    let mut p = Particles::default();
    let mut rng = saltus_core::rng::stream(7, 0);
    use rand::Rng as _;
    let per_side = 7;
    for k in 0..per_side * per_side * per_side {
        let (ix, iy, iz) = (k % per_side, (k / per_side) % per_side, k / (per_side * per_side));
        let c = |i: usize| (i as f64 + 0.5) * l / per_side as f64;
        let v = [0; 3].map(|_| 4.0 * (2.0 * rng.gen::<f64>() - 1.0));
        p.push([c(ix), c(iy), c(iz)], v, [0.0; 3], r, 2500.0, false);
    }
    let law = ContactLaw::linear(3e4, 1.5e4, 0.9, 0.5);
    let m = 2500.0 * std::f64::consts::PI * (2.0 * r).powi(3) / 6.0;
    let dt = 0.22 * law.contact_time(m, r, 2500.0, 0.0, 0.0);
    let mut dem = Dem::new(p, bx, law, Vec::new(), [0.0; 3], dt, 0.01 * 2.0 * r);
    let mut widest: f64 = 0.0;
    for step in 0..400 {
        dem.step();
        widest = widest.max(dem.list.skin);
        if dem.rebuild_due {
            continue;
        }
        let (p, list) = (&dem.p, &dem.list);
        for (a, b) in pairs_within(p, &bx, 0.0) {
            let listed = (list.start[a]..list.start[a + 1]).any(|q| list.j[q] as usize == b);
            assert!(listed, "step {step}: pair ({a}, {b}) in contact is not listed");
        }
    }
    assert!(dem.list.builds > 10, "{} builds", dem.list.builds);
    assert!(widest > 5.0 * dem.list.skin_min && widest <= MAX_SKIN_DIAMETERS * 2.0 * r, "skin {widest}");
}
