//! The limits a model declares ([`Limit`]) checked along a sequence of inputs.

use super::*;

/// Whether the values `v_k` at `x_k` (towards the limit) tend to `target`: the last is
/// within 1e-3 (relative, absolute below 1), or the errors shrink geometrically (each at
/// most 0.9 times the previous: a slowly converging power law).
pub(super) fn tends_to(what: &str, xs: &[f64], values: &[f64], target: f64) -> Result<(), String> {
    let err: Vec<f64> = values.iter().map(|v| (v - target).abs() / target.abs().max(1.0)).collect();
    let shown = || {
        xs.iter().zip(values).map(|(x, v)| format!("{} at {}", number(*v), number(*x))).collect::<Vec<_>>().join(", ")
    };
    if values.iter().any(|v| !v.is_finite()) {
        return Err(format!("{what} not finite on the way to the limit: {}", shown()));
    }
    let last = err.last().copied().unwrap_or(f64::INFINITY);
    let shrinking = err.windows(2).all(|w| w[1] <= 0.9 * w[0]);
    if last <= 1e-3 || shrinking {
        Ok(())
    } else {
        Err(format!("{what} does not tend to {}: {}", number(target), shown()))
    }
}

pub(super) fn limit_name(l: Limit) -> (&'static str, String) {
    match l {
        Limit::Stokes { cd_re } => ("limit stokes", format!("C_D Re_p -> {} as Re_p -> 0", number(cd_re))),
        Limit::HighReynolds => ("limit high Re", "C_D -> cd_inf as Re_p -> inf".into()),
        Limit::Dilute => ("limit dilute", "factor -> 1 as phi -> 0".into()),
        Limit::Einstein { coefficient } => {
            ("limit einstein", format!("nu_eff/nu_f = 1 + {} phi + O(phi^2)", number(coefficient)))
        }
        Limit::Decreasing => ("decreasing", "main output non-increasing in its input".into()),
        Limit::Increasing => ("increasing", "main output non-decreasing in its input".into()),
        Limit::StaticFriction { mu_s } => {
            ("limit static", format!("mu -> mu_s = {} as the control number -> 0", number(mu_s)))
        }
        Limit::PackingDecreasing => ("packing decreasing", "phi non-increasing in the control number".into()),
        Limit::WallLength { kappa } => {
            ("limit wall", format!("l_m / z -> kappa = {} as z -> 0 in clear fluid", number(kappa)))
        }
        Limit::NonNegative => ("non-negative", "diffusivity D >= 0".into()),
        _ => ("limit", "unknown limit".into()),
    }
}

/// The limit `index` that the model declares, as declared by `m` itself: a limit may
/// depend on the parameters (Dallavalle's C_D Re_p -> a).
pub(super) fn own_limit(m: &Built, index: usize) -> Result<Limit, String> {
    m.describe()
        .limits()
        .get(index)
        .copied()
        .ok_or_else(|| "the model declares fewer limits with these parameters".into())
}

pub(super) fn declared_limit(space: &ParamSpace, family: Family, index: usize, limit: Limit, opts: Options) -> Outcome {
    let (name, what) = limit_name(limit);
    let small = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10];
    let large = [1e4, 1e6, 1e8, 1e10, 1e12];
    let applies = match limit {
        Limit::Stokes { .. } | Limit::HighReynolds => family == Family::Drag,
        // kinetic theory: g0 -> 1
        Limit::Dilute => matches!(family, Family::Hindrance | Family::Viscosity | Family::Granular),
        Limit::StaticFriction { .. } | Limit::PackingDecreasing => family == Family::Granular,
        Limit::WallLength { .. } => family == Family::Turbulence,
        Limit::NonNegative => family == Family::Fluctuation,
        Limit::Einstein { .. } => family == Family::Viscosity,
        Limit::Decreasing | Limit::Increasing => {
            matches!(
                family,
                Family::Drag | Family::Hindrance | Family::Viscosity | Family::Granular | Family::WallFriction
            )
        }
        _ => false,
    };
    if !applies {
        return fail(name, format!("declared, but it does not apply to the {family} family"), None);
    }
    let increasing = matches!(limit, Limit::Increasing);
    match limit {
        Limit::NonNegative => {
            let prop = |m: &Built, x: &Vec<f64>| match m {
                Built::Fluctuation(m) => {
                    let (t, _, s) = evaluate::fluctuation_point(x);
                    let d = m.diffusivity(&t, &s);
                    // NaN fails too
                    if d >= 0.0 {
                        Ok(())
                    } else {
                        Err(format!("D = {}", number(d)))
                    }
                }
                _ => Err("not applicable".into()),
            };
            let show = move |x: &Vec<f64>| show_inputs(family, x);
            run_property(
                name,
                (space, family, opts),
                inputs(family),
                show,
                prop,
                format!("{what}: {} cases", opts.cases),
            )
        }
        Limit::PackingDecreasing => {
            let pair: BoxedStrategy<Vec<f64>> = vec![log_uniform(1e-8, 1e3), log_uniform(1e-6, 1e2)].boxed();
            let show = |x: &Vec<f64>| format!("x = {}, x * (1 + {})", number(x[0]), number(x[1]));
            let prop = |m: &Built, x: &Vec<f64>| {
                let Built::Granular(m) = m else { return Err("not applicable".into()) };
                let l = m.as_local().ok_or("the packing is checked on local rheologies (phi of I or K)")?;
                let x2 = x[0] * (1.0 + x[1]);
                let (a, b) = (l.packing(x[0]), l.packing(x2));
                if b <= a + 1e-12 * a.abs().max(b.abs()) {
                    Ok(())
                } else {
                    Err(format!("phi = {} at {} then {} at {}", number(a), number(x[0]), number(b), number(x2)))
                }
            };
            run_property(name, (space, family, opts), pair, show, prop, format!("{what}: {} pairs", opts.cases))
        }
        Limit::Decreasing | Limit::Increasing => {
            // two inputs x1 < x2 (and the other inputs shared)
            let pair: BoxedStrategy<Vec<f64>> = match family {
                Family::Drag => vec![reynolds(), log_uniform(1e-6, 1e2)].boxed(),
                Family::Hindrance => vec![(0.0..=0.6).boxed(), (0.0..=0.3).boxed(), reynolds()].boxed(),
                Family::Viscosity => vec![(0.0..0.999).boxed(), (0.0..=0.5).boxed()].boxed(),
                Family::WallFriction => vec![log_uniform(1e-6, 1e9), log_uniform(1e-6, 1e2)].boxed(),
                _ => vec![log_uniform(1e-8, 1e3), log_uniform(1e-6, 1e2)].boxed(),
            };
            let show = move |x: &Vec<f64>| match family {
                Family::Drag => format!("re_p = {}, re_p * (1 + {})", number(x[0]), number(x[1])),
                Family::WallFriction => format!("re = {}, re * (1 + {})", number(x[0]), number(x[1])),
                Family::Hindrance => {
                    format!("phi = {} and {}, re_p = {}", number(x[0]), number((x[0] + x[1]).min(0.9)), number(x[2]))
                }
                Family::Viscosity => {
                    format!("phi/phi_limit = {} and {}", number(x[0]), number((x[0] + x[1]).min(0.999)))
                }
                _ => format!("x = {}, x * (1 + {})", number(x[0]), number(x[1])),
            };
            let prop = move |m: &Built, x: &Vec<f64>| {
                let (a, b, x1, x2) = match m {
                    Built::Drag(m) => {
                        let x2 = x[0] * (1.0 + x[1]);
                        (m.cd(x[0]), m.cd(x2), x[0], x2)
                    }
                    Built::WallFriction(m) => {
                        let x2 = x[0] * (1.0 + x[1]);
                        (m.friction_factor(x[0]), m.friction_factor(x2), x[0], x2)
                    }
                    Built::Hindrance(m) => {
                        let p2 = (x[0] + x[1]).min(0.9);
                        (m.factor(x[0], x[2]), m.factor(p2, x[2]), x[0], p2)
                    }
                    Built::Viscosity(m) => {
                        let lim = m.phi_limit().min(1.0);
                        let (p1, p2) = (x[0] * lim, (x[0] + x[1]).min(0.999) * lim);
                        (m.ratio(p1), m.ratio(p2), p1, p2)
                    }
                    Built::Granular(m) => match m.as_local() {
                        Some(l) => {
                            let x2 = x[0] * (1.0 + x[1]);
                            (l.friction(x[0]), l.friction(x2), x[0], x2)
                        }
                        None => return Err("monotonicity is checked on local rheologies (mu of I or K)".into()),
                    },
                    _ => return Err("not applicable".into()),
                };
                let slack = 1e-12 * a.abs().max(b.abs());
                let ok = if increasing { b >= a - slack } else { b <= a + slack };
                if ok {
                    Ok(())
                } else {
                    Err(format!("{} at {} then {} at {}", number(a), number(x1), number(b), number(x2)))
                }
            };
            run_property(name, (space, family, opts), pair, show, prop, format!("{what}: {} pairs", opts.cases))
        }
        _ => {
            let input: BoxedStrategy<Vec<f64>> =
                if family == Family::Hindrance { vec![reynolds()].boxed() } else { Just(Vec::new()).boxed() };
            let show = |x: &Vec<f64>| x.first().map_or_else(String::new, |r| format!("re_p = {}", number(*r)));
            let prop = move |m: &Built, x: &Vec<f64>| match (m, own_limit(m, index)?) {
                (Built::Drag(m), Limit::Stokes { cd_re }) => {
                    tends_to("C_D Re_p", &small, &small.map(|r| m.cd_re(r)), cd_re)
                }
                (Built::Drag(m), Limit::HighReynolds) => tends_to("C_D", &large, &large.map(|r| m.cd(r)), m.cd_inf()),
                (Built::Hindrance(m), Limit::Dilute) => tends_to("f", &small, &small.map(|p| m.factor(p, x[0])), 1.0),
                // towards 0 from inside the law's domain (phi_m of Krieger-Dougherty may be small)
                (Built::Viscosity(m), Limit::Dilute) => {
                    let phi = small.map(|p| p * m.phi_limit().min(1.0));
                    tends_to("nu_eff/nu_f", &phi, &phi.map(|p| m.ratio(p)), 1.0)
                }
                (Built::Granular(m), Limit::StaticFriction { mu_s }) => {
                    let l = m.as_local().ok_or("the static friction is checked on local rheologies (mu of I or K)")?;
                    tends_to("mu", &small, &small.map(|x| l.friction(x)), mu_s)?;
                    // at rest itself, I = 0 (a state of no shear)
                    let at_rest = l.friction(0.0);
                    if (at_rest - mu_s).abs() <= 1e-12 * mu_s.abs().max(1.0) {
                        Ok(())
                    } else {
                        Err(format!("mu = {} at 0, not mu_s = {}", number(at_rest), number(mu_s)))
                    }
                }
                (Built::Granular(m), Limit::Dilute) => {
                    let k =
                        m.as_kinetic().ok_or("the dilute limit of a granular stress is g0 -> 1 of kinetic theory")?;
                    let phi = small.map(|p| p * k.phi_max());
                    tends_to("g0", &phi, &phi.map(|p| k.coefficients(p, None).g0), 1.0)
                }
                (Built::Turbulence(m), Limit::WallLength { kappa }) => {
                    // clear-fluid columns of 20 cells ever thinner: l_m / z of the first cell
                    let heights = small.map(|h| 10.0 * h);
                    let ratios = heights.map(|h| evaluate::wall_ratio(m.as_ref(), h));
                    let z = heights.map(|h| h / 40.0);
                    tends_to("l_m / z", &z, &ratios, kappa)
                }
                (Built::Viscosity(m), Limit::Einstein { coefficient }) => {
                    let phi = small.map(|p| p * m.phi_limit().min(1.0));
                    tends_to("(nu_eff/nu_f - 1)/phi", &phi, &phi.map(|p| (m.ratio(p) - 1.0) / p), coefficient)
                }
                _ => Err("not applicable".into()),
            };
            run_property(name, (space, family, opts), input, show, prop, what)
        }
    }
}
