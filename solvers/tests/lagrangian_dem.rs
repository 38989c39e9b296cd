use saltus_solvers::lagrangian::*;

fn two(v: f64, e: f64, steps: f64) -> Dem {
    let mut p = Particles::default();
    let r = 0.003;
    p.push([0.0, 0.0, 0.0], [v, 0.0, 0.0], [0.0; 3], r, 2500.0, false);
    p.push([2.0 * r + 1e-4, 0.0, 0.0], [-v, 0.0, 0.0], [0.0; 3], r, 2500.0, false);
    let law = ContactLaw::linear(1e4, 1e4, e, 0.4);
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let tc = law.contact_time(m, r, 2500.0, 0.0, 0.0);
    let bx = Box3 { length: [1.0; 3], periodic: [false; 3] };
    Dem::new(p, bx, law, vec![], [0.0; 3], tc / steps, 0.2 * r)
}

#[test]
fn smoke_collision() {
    for steps in [25.0, 50.0, 100.0, 200.0, 400.0] {
    let mut d = two(0.1, 0.7, steps);
    for _ in 0..(steps as usize * 40) {
        d.step();
    }
    let e = (d.p.vx[1] - d.p.vx[0]) / 0.2;
    println!("{steps} e = {e}");
    }
    let e: f64 = 0.7;
    assert!((e - 0.7).abs() < 0.007);
}
