//! Closure outputs at the drawn inputs: finite values and batch against scalar.

use super::*;

pub(super) fn finite_or(what: &str, v: f64) -> Result<(), String> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} = {}", number(v)))
    }
}

/// The 20-cell column of the turbulence checks: a bed of volume fraction `phi_bed` over
/// the lowest 2 cm, clear fluid above, uniform shear `dudz`.
pub(super) struct Column {
    z: Vec<f64>,
    dz: Vec<f64>,
    phi: Vec<f64>,
    dudz: Vec<f64>,
    k: Vec<f64>,
    omega: Vec<f64>,
}

impl Column {
    fn new(phi_bed: f64, dudz: f64) -> Self {
        let n = 20;
        let dz = 0.1 / n as f64;
        let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * dz).collect();
        let phi = z.iter().map(|&z| if z < 0.02 { phi_bed } else { 0.0 }).collect();
        Self { dz: vec![dz; n], phi, dudz: vec![dudz; n], k: vec![1e-4; n], omega: vec![10.0; n], z }
    }
}

pub(super) fn turbulence_eval(m: &dyn Turbulence, x: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let c = Column::new(x[1], x[2]);
    let transported: Vec<&[f64]> = match m.transported().len() {
        0 => Vec::new(),
        _ => vec![&c.k, &c.omega],
    };
    let col = ColumnView {
        z: &c.z,
        dz: &c.dz,
        phi: &c.phi,
        dudz: &c.dudz,
        diameter: x[0],
        nu_f: 1e-6,
        transported: &transported,
    };
    let mut lm = vec![0.0; c.z.len()];
    m.mixing_length(&col, &mut lm);
    let mut nut = vec![0.0; c.z.len()];
    m.eddy_viscosity(&col, &mut nut);
    let point = match m.as_two_equation() {
        Some(te) => c.k.iter().zip(&c.omega).map(|(&k, &w)| te.eddy_viscosity_of(k.max(0.0), w, col.nu_f)).collect(),
        None => lm.iter().zip(&c.dudz).map(|(&l, &g)| m.eddy_viscosity_point(l, g)).collect(),
    };
    (lm, nut, point)
}

/// l_m / z at the centre of the lowest of 20 cells of a clear-fluid column `height` high,
/// sheared at 10 1/s, grains of 1 mm.
pub(super) fn wall_ratio(m: &dyn Turbulence, height: f64) -> f64 {
    let n = 20;
    let dz = height / n as f64;
    let z: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * dz).collect();
    let (widths, phi, dudz) = (vec![dz; n], vec![0.0; n], vec![10.0; n]);
    let (k, omega) = (vec![1e-4; n], vec![10.0; n]);
    let transported: Vec<&[f64]> = match m.transported().len() {
        0 => Vec::new(),
        _ => vec![&k, &omega],
    };
    let col = ColumnView {
        z: &z,
        dz: &widths,
        phi: &phi,
        dudz: &dudz,
        diameter: 1e-3,
        nu_f: 1e-6,
        transported: &transported,
    };
    let mut lm = vec![0.0; n];
    m.mixing_length(&col, &mut lm);
    lm[0] / z[0]
}

pub(super) fn fluctuation_point(x: &[f64]) -> (TurbulencePoint, ParticleSlip, FlowScales) {
    (
        TurbulencePoint { k: x[0], omega: x[1], nu_t: x[2], reynolds_stress: x[3] },
        ParticleSlip { slip: x[4], response_time: x[5] },
        FlowScales { depth: x[6], bulk_velocity: x[7] },
    )
}

pub(super) fn finite_at(m: &Built, x: &[f64]) -> Result<(), String> {
    match m {
        Built::Drag(m) => {
            finite_or("C_D", m.cd(x[0]))?;
            finite_or("C_D Re_p", m.cd_re(x[0]))
        }
        Built::Hindrance(m) => finite_or("f", m.factor(x[0], x[1])),
        Built::Viscosity(m) => {
            let phi = x[0] * m.phi_limit().min(1.0);
            finite_or(&format!("nu_eff/nu_f at phi = {}", number(phi)), m.ratio(phi))
        }
        Built::Granular(m) => {
            if let Some(l) = m.as_local() {
                finite_or("mu", l.friction(x[0]))?;
                finite_or("phi", l.packing(x[0]))
            } else if let Some(k) = m.as_kinetic() {
                let phi = (x[0] / 1e3).min(0.999) * k.phi_max();
                let c = k.coefficients(phi, None);
                for (n, v) in [("g0", c.g0), ("F1", c.f1), ("F2", c.f2), ("F3", c.f3), ("F4", c.f4), ("e_eff", c.e_eff)]
                {
                    finite_or(&format!("{n} at phi = {}", number(phi)), v)?;
                }
                Ok(())
            } else {
                Err("neither a local rheology nor a kinetic theory".into())
            }
        }
        Built::Turbulence(m) => {
            let (lm, nut, _) = turbulence_eval(m.as_ref(), x);
            for (i, (l, n)) in lm.iter().zip(&nut).enumerate() {
                finite_or(&format!("l_m of cell {i}"), *l)?;
                finite_or(&format!("nu_t of cell {i}"), *n)?;
            }
            Ok(())
        }
        Built::Fluctuation(m) => {
            let (t, p, s) = fluctuation_point(x);
            finite_or("diffusivity", m.diffusivity(&t, &s))?;
            let mut rng = saltus_core::rng::stream(0, 0);
            let d = m.draw(&t, &p, &s, &mut rng);
            for (n, v) in ["u_x", "u_y", "u_z"].iter().zip(d.u) {
                finite_or(n, v)?;
            }
            // +inf is the documented duration of a closure that draws nothing
            if d.duration.is_nan() || d.duration < 0.0 {
                return Err(format!("duration = {}", number(d.duration)));
            }
            Ok(())
        }
        Built::WallFriction(m) => {
            finite_or("f", m.friction_factor(x[0]))?;
            finite_or("f Re", m.poiseuille_number(x[0]))
        }
    }
}

pub(super) fn finite(space: &ParamSpace, family: Family, opts: Options) -> Outcome {
    let ranges = match family {
        Family::Drag => "Re_p in [1e-6, 1e6]",
        Family::Hindrance => "phi in [0, 0.6], Re_p in [1e-6, 1e6]",
        Family::Viscosity => "phi in [0, 0.999 phi_limit)",
        Family::Granular => "I or K in [1e-8, 1e3] (kinetic theory: phi below phi_max)",
        Family::Turbulence => "d in [1e-5, 1e-2] m, phi_bed in [0, 0.6], dudz in [0, 100] 1/s",
        Family::Fluctuation => "turbulence, slip and flow scales of open-channel flows",
        Family::WallFriction => "Re in [1e-6, 1e9]",
    };
    run_property(
        "finite",
        (space, family, opts),
        inputs(family),
        |x| show_inputs(family, x),
        |m, x| finite_at(m, x),
        format!("{} cases: finite output for {ranges}, parameters within their ranges", opts.cases),
    )
}

pub(super) fn batch_at(m: &Built, xs: &[Vec<f64>]) -> Result<(), String> {
    let col = |i: usize| xs.iter().map(|x| x[i]).collect::<Vec<f64>>();
    let cmp = |what: &str, batch: &[f64], scalar: &[f64]| -> Result<(), String> {
        for (i, (b, s)) in batch.iter().zip(scalar).enumerate() {
            if !same(*b, *s) {
                return Err(format!("{what}: batch {} != scalar {} at point {i}", number(*b), number(*s)));
            }
        }
        Ok(())
    };
    let n = xs.len();
    let mut out = vec![0.0; n];
    match m {
        Built::Drag(m) => {
            let re = col(0);
            m.cd_batch(&re, &mut out);
            cmp("C_D", &out, &re.iter().map(|&r| m.cd(r)).collect::<Vec<_>>())?;
            m.cd_re_batch(&re, &mut out);
            cmp("C_D Re_p", &out, &re.iter().map(|&r| m.cd_re(r)).collect::<Vec<_>>())
        }
        Built::Hindrance(m) => {
            let (phi, re) = (col(0), col(1));
            m.factor_batch(&phi, &re, &mut out);
            cmp("f", &out, &phi.iter().zip(&re).map(|(&p, &r)| m.factor(p, r)).collect::<Vec<_>>())
        }
        Built::Viscosity(m) => {
            let phi: Vec<f64> = col(0).iter().map(|u| u * m.phi_limit().min(1.0)).collect();
            m.ratio_batch(&phi, &mut out);
            cmp("nu_eff/nu_f", &out, &phi.iter().map(|&p| m.ratio(p)).collect::<Vec<_>>())
        }
        Built::Granular(m) => {
            let x = col(0);
            if let Some(l) = m.as_local() {
                let mut phi = vec![0.0; n];
                l.eval_batch(&x, &mut out, &mut phi);
                cmp("mu", &out, &x.iter().map(|&v| l.friction(v)).collect::<Vec<_>>())?;
                cmp("phi", &phi, &x.iter().map(|&v| l.packing(v)).collect::<Vec<_>>())?;
                let packing: Vec<f64> = x.iter().map(|&v| l.packing(v)).collect();
                l.control_of_packing_batch(&packing, &mut out);
                cmp("control_of_packing", &out, &packing.iter().map(|&p| l.control_of_packing(p)).collect::<Vec<_>>())
            } else if let Some(k) = m.as_kinetic() {
                let phi: Vec<f64> = x.iter().map(|v| (v / 1e3).min(0.999) * k.phi_max()).collect();
                let mut c = vec![saltus_core::KineticCoefficients::default(); n];
                k.coefficients_batch(&phi, None, &mut c);
                for (i, (b, &p)) in c.iter().zip(&phi).enumerate() {
                    let s = k.coefficients(p, None);
                    let pairs =
                        [(b.g0, s.g0), (b.f1, s.f1), (b.f2, s.f2), (b.f3, s.f3), (b.f4, s.f4), (b.e_eff, s.e_eff)];
                    if !pairs.iter().all(|(a, b)| same(*a, *b)) {
                        return Err(format!("coefficients: batch {b:?} != scalar {s:?} at point {i}"));
                    }
                }
                let cd: Vec<f64> = x.iter().map(|v| 0.4 + 24.0 / v.max(1e-300)).collect();
                k.drag_dissipation_batch(0.4, &cd, &mut out);
                cmp("c_J", &out, &cd.iter().map(|&c| k.drag_dissipation_factor(0.4, c)).collect::<Vec<_>>())
            } else {
                Err("neither a local rheology nor a kinetic theory".into())
            }
        }
        Built::Turbulence(m) => {
            for x in xs {
                let (_, nut, point) = turbulence_eval(m.as_ref(), x);
                cmp("nu_t (column vs point)", &nut, &point)?;
            }
            Ok(())
        }
        Built::Fluctuation(m) => {
            // one column shares its flow scales; the points differ
            let (_, _, s) = fluctuation_point(&xs[0]);
            let t: Vec<TurbulencePoint> = xs.iter().map(|x| fluctuation_point(x).0).collect();
            m.diffusivity_batch(&t, &s, &mut out);
            cmp("diffusivity", &out, &t.iter().map(|t| m.diffusivity(t, &s)).collect::<Vec<_>>())?;
            // the draws of a chunk, each from its own stream, against one draw per point
            let p: Vec<ParticleSlip> = xs.iter().map(|x| fluctuation_point(x).1).collect();
            let streams = || (0..n as u64).map(|i| saltus_core::rng::stream(0, i)).collect::<Vec<_>>();
            let (mut a, mut b) = (streams(), streams());
            let mut draws = vec![saltus_core::FluctuationDraw::default(); n];
            m.draw_batch(&t, &p, &s, &mut a.iter_mut().collect::<Vec<_>>(), &mut draws);
            for (i, (d, r)) in draws.iter().zip(b.iter_mut()).enumerate() {
                let one = m.draw(&t[i], &p[i], &s, r);
                let pairs = [(d.u[0], one.u[0]), (d.u[1], one.u[1]), (d.u[2], one.u[2]), (d.duration, one.duration)];
                if !pairs.iter().all(|(x, y)| same(*x, *y)) {
                    return Err(format!("draws: batch {d:?} != one per particle {one:?} at point {i}"));
                }
            }
            Ok(())
        }
        Built::WallFriction(m) => {
            let re = col(0);
            out.copy_from_slice(&re);
            m.poiseuille_batch(&mut out);
            cmp("f Re", &out, &re.iter().map(|&r| m.poiseuille_number(r)).collect::<Vec<_>>())
        }
    }
}

pub(super) fn batch(space: &ParamSpace, family: Family, opts: Options) -> Outcome {
    run_property(
        "batch = scalar",
        (space, family, opts),
        vec(inputs(family), 1..12).boxed(),
        |xs| xs.iter().map(|x| format!("[{}]", show_inputs(family, x))).collect::<Vec<_>>().join(" "),
        |m, xs| batch_at(m, xs),
        format!("{} cases of 1 to 11 points: every batch method equals its scalar method bit for bit", opts.cases),
    )
}
