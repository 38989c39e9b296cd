//! The bounds of the calibrated constants as the optimiser sees them: the transformation of
//! MINUIT (James & Roos 1975; the one lmfit uses), p = lo + (hi - lo) (sin u + 1) / 2 with
//! u free, its inverse and derivative, and whether a start is resolved by it.

/// p of u inside [lo, hi].
pub fn to_p(u: f64, [lo, hi]: [f64; 2]) -> f64 {
    lo + (hi - lo) * (u.sin() + 1.0) / 2.0
}

/// u of p (p inside the bounds).
pub fn to_u(p: f64, [lo, hi]: [f64; 2]) -> f64 {
    (2.0 * (p - lo) / (hi - lo) - 1.0).clamp(-1.0, 1.0).asin()
}

/// Whether the transformation carries `p` inside `bounds` to u and back to within 1e-9
/// of its size: bounds so wide against the start that it is lost (or whose span
/// overflows) leave the optimiser no resolution where it begins.
pub fn resolves(p: f64, bounds: [f64; 2]) -> bool {
    let span = bounds[1] - bounds[0];
    let scale = if p != 0.0 { p.abs() } else { span };
    span.is_finite() && (to_p(to_u(p, bounds), bounds) - p).abs() <= 1e-9 * scale
}

/// dp/du at u.
pub fn dp_du(u: f64, [lo, hi]: [f64; 2]) -> f64 {
    (hi - lo) * u.cos() / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bounds_transformation_is_inverted_and_stays_inside() {
        let b = [0.2, 3.0];
        for p in [0.2000001, 0.5, 1.7, 2.9999] {
            let u = to_u(p, b);
            assert!((to_p(u, b) - p).abs() < 1e-12);
            let h = 1e-7;
            let fd = (to_p(u + h, b) - to_p(u - h, b)) / (2.0 * h);
            assert!((fd - dp_du(u, b)).abs() < 1e-6);
        }
        for u in [-10.0, -1.0, 0.0, 2.0, 100.0] {
            let p = to_p(u, b);
            assert!((0.2..=3.0).contains(&p));
        }
    }

    #[test]
    fn bounds_too_wide_for_the_start_are_told_apart() {
        assert!(resolves(0.05, [0.01, 0.5]));
        assert!(resolves(0.0, [-1.0, 1.0]));
        assert!(resolves(1e-3, [0.0, 1.0]));
        // the start is lost in the span: u maps back to the lower bound
        assert!(!resolves(0.05, [0.01, 1e308]));
        // the span overflows
        assert!(!resolves(0.0, [-1e308, 1e308]));
    }
}
