//! Tests of the neighbour list: the skin policy, the grid bounds, the parallel build
//! against the serial one and brute force, the contact histories across rebuilds.

use super::*;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn lists_every_close_pair_once(
        pts in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0), 2..120),
        periodic_y in any::<bool>(),
    ) {
        // brute force over all pairs and images against the cell-list build
        let (l, r, skin) = (1.0, 0.04, 0.02);
        let bx = Box3 { length: [l, l, 0.0], periodic: [true, periodic_y, false] };
        let mut p = Particles::default();
        for &(x, y, z) in &pts {
            p.push([x, y, z], [0.0; 3], [0.0; 3], r, 1000.0, false);
        }
        let mut list = NeighbourList::new(skin);
        list.build(&mut p, &bx);
        let expected: Vec<(u32, u32)> =
            pairs_within(&p, &bx, skin).into_iter().map(|(a, b)| (a as u32, b as u32)).collect();
        let mut got: Vec<(u32, u32)> = list.i.iter().zip(&list.j).map(|(a, b)| (*a, *b)).collect();
        got.sort_unstable();
        prop_assert_eq!(got, expected);
        // the reverse index lists each pair once under its j
        let mut seen = vec![0; list.len()];
        for b in 0..p.len() {
            for &q in &list.rev[list.rev_start[b]..list.rev_start[b + 1]] {
                prop_assert_eq!(list.j[q as usize] as usize, b);
                seen[q as usize] += 1;
            }
        }
        prop_assert!(seen.iter().all(|&c| c == 1));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn an_adapted_skin_misses_no_contact(
        pts in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.0f64..0.6, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 40..150),
        kick in 0usize..40,
    ) {
        // grains moving at up to 2 m/s, one of them kicked to 20 m/s after `kick`
        // steps: the skin grows from 1 % of d and must shrink again; after every step
        // the list the next step would use holds every pair in contact
        let (l, r, dt) = (1.0, 0.04, 1e-4);
        let bx = Box3 { length: [l, l, 0.0], periodic: [true, true, false] };
        let mut p = Particles::default();
        for &(x, y, z, vx, vy, vz) in &pts {
            p.push([x, y, z], [2.0 * vx, 2.0 * vy, 2.0 * vz], [0.0; 3], r, 1000.0, false);
        }
        let mut list = NeighbourList::new(0.02 * r);
        list.build(&mut p, &bx);
        let mut grew = false;
        for step in 0..120 {
            if step == kick {
                p.vx[0] = 20.0;
            }
            for a in 0..p.len() {
                p.x[a] += p.vx[a] * dt;
                p.y[a] += p.vy[a] * dt;
                p.z[a] += p.vz[a] * dt;
            }
            list.tick();
            if list.needs_rebuild(&p) {
                list.build(&mut p, &bx);
            }
            grew |= list.skin > 2.0 * list.skin_min;
            prop_assert!(list.skin >= list.skin_min && list.skin <= MAX_SKIN_DIAMETERS * 2.0 * r);
            for (a, b) in pairs_within(&p, &bx, 0.0) {
                let row = list.start[a]..list.start[a + 1];
                let q = row.clone().find(|&q| list.j[q] as usize == b);
                prop_assert!(q.is_some(), "step {step}: pair ({a}, {b}) in contact is not listed");
                // and with the image the list froze
                let (q, s) = (q.unwrap_or(0), list.shift[q.unwrap_or(0)]);
                let d = [p.x[b] + s[0] - p.x[a], p.y[b] + s[1] - p.y[a], p.z[b] + s[2] - p.z[a]];
                prop_assert!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 4.0 * r * r, "pair {q}");
            }
        }
        prop_assert!(grew, "the skin never adapted");
    }
}

#[test]
fn the_skin_follows_the_steps_between_builds() {
    let mut list = NeighbourList::new(1e-4);
    list.skin = 4e-4;
    // built too often: wider, by at most a factor 2 and to at most the bound
    assert_eq!(list.adapted_skin(1, 1.0), 8e-4);
    assert!((list.adapted_skin(10, 1.0) / 4e-4 - (TARGET_STEPS / 10.0).sqrt()).abs() < 1e-12);
    assert_eq!(list.adapted_skin(1, 5e-4), 5e-4);
    // at the target: kept; too seldom: narrower, by at most a factor 2, never below
    // the smallest
    assert_eq!(list.adapted_skin(TARGET_STEPS as u64, 1.0), 4e-4);
    assert_eq!(list.adapted_skin(10_000, 1.0), 2e-4);
    list.skin = 1.5e-4;
    assert_eq!(list.adapted_skin(10_000, 1.0), 1e-4);
}

#[test]
fn the_grid_is_bounded_by_the_particles() {
    // two grains far apart in a wide box: the full grid would hold 1e17 cells
    let bx = Box3 { length: [60.0, 60.0, 0.0], periodic: [true, true, false] };
    let mut p = Particles::default();
    p.push([1.0, 1.0, 0.01], [0.0; 3], [0.0; 3], 3e-3, 2500.0, false);
    p.push([1.0, 1.0, 1e6], [0.0; 3], [0.0; 3], 3e-3, 2500.0, false);
    p.push([1.004, 1.0, 1e6 + 0.004], [0.0; 3], [0.0; 3], 3e-3, 2500.0, false);
    let mut list = NeighbourList::new(6e-4);
    list.build(&mut p, &bx);
    assert!(list.cell_start.len() <= MIN_CELL_CAP + 1);
    assert_eq!((list.len(), list.i[0], list.j[0]), (1, 1, 2));
}

#[test]
fn the_parallel_build_is_the_serial_one_and_carries_every_history() {
    // 900 grains (four chunks of rows) in a periodic box: the list built on two
    // threads is the one built on one, pair for pair, and holds exactly the close
    // pairs (brute force); after a move, every pair that survives keeps its history
    let (l, r, skin) = (0.1, 3e-3, 1e-3);
    let bx = Box3 { length: [l, l, 0.0], periodic: [true, true, false] };
    let mut rng = saltus_core::rng::stream(3, 0);
    use rand::Rng as _;
    let mut p = Particles::default();
    for _ in 0..900 {
        let pos = [l * rng.gen::<f64>(), l * rng.gen::<f64>(), 0.05 * rng.gen::<f64>()];
        p.push(pos, [0.0; 3], [0.0; 3], r, 2500.0, false);
    }
    let build = |threads: usize, p: &mut Particles, list: &mut NeighbourList| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| list.build(p, &bx));
    };
    let (mut one, mut two) = (NeighbourList::new(skin), NeighbourList::new(skin));
    build(1, &mut p.clone(), &mut one);
    build(2, &mut p, &mut two);
    assert!(one.len() > 2 * CHUNK, "{} pairs", one.len());
    assert_eq!((&one.i, &one.j, &one.shift, &one.start), (&two.i, &two.j, &two.shift, &two.start));
    let mut got: Vec<(usize, usize)> = two.i.iter().zip(&two.j).map(|(&a, &b)| (a as usize, b as usize)).collect();
    got.sort_unstable();
    assert_eq!(got, pairs_within(&p, &bx, skin));
    // a history per pair that names it, then a move of at most 0.2 skin and a rebuild,
    // which doubles the skin (one step since the build): every pair survives
    let before = two.len();
    for q in 0..two.len() {
        two.hist[q] = [two.i[q] as f64, two.j[q] as f64, 1.0];
    }
    for a in 0..p.len() {
        p.x[a] += 0.2 * skin * (2.0 * rng.gen::<f64>() - 1.0);
    }
    two.steps_since = 1;
    build(2, &mut p, &mut two);
    let carried = (0..two.len()).filter(|&q| two.hist[q][2] == 1.0).count();
    for q in 0..two.len() {
        let h = two.hist[q];
        assert!(h == [0.0; 3] || h == [two.i[q] as f64, two.j[q] as f64, 1.0], "pair {q}: {h:?}");
    }
    assert!(two.skin > 1.5 * skin);
    assert_eq!(carried, before, "{carried} of {before} histories carried");
}

#[test]
fn history_survives_a_rebuild() {
    let bx = Box3 { length: [1.0, 1.0, 0.0], periodic: [true, true, false] };
    let mut p = Particles::default();
    p.push([0.99, 0.5, 0.5], [0.0; 3], [0.0; 3], 0.02, 1000.0, false);
    p.push([0.02, 0.5, 0.5], [0.0; 3], [0.0; 3], 0.02, 1000.0, false);
    let mut list = NeighbourList::new(0.01);
    list.build(&mut p, &bx);
    assert_eq!(list.len(), 1);
    assert!((list.shift[0][0] - 1.0).abs() < 1e-15 || (list.shift[0][0] + 1.0).abs() < 1e-15);
    list.hist[0] = [1e-5, 2e-5, 0.0];
    // particle 0 crosses the periodic boundary before the next build
    p.x[0] = 1.001;
    list.build(&mut p, &bx);
    assert_eq!(list.len(), 1);
    assert_eq!(list.hist[0], [1e-5, 2e-5, 0.0]);
    assert!(p.x[0] < 0.01);
}
