//! The grammar of a parameter's range, read once for the two places that read it: the
//! `range` attribute of `#[derive(Describe)]` (at compile time, in `saltus-derive`) and
//! `ParamRange::from_str` (at run time, a closure registered from Python, in
//! `saltus-core`). It has no dependency so that the procedural-macro crate can use it.

/// One end of an interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    /// `-inf` or `inf` (always open)
    Unbounded,
    /// excluded
    Open(f64),
    /// included
    Closed(f64),
}

impl End {
    fn value(self, infinity: f64) -> f64 {
        match self {
            End::Open(x) | End::Closed(x) => x,
            End::Unbounded => infinity,
        }
    }
}

/// The two ends of `text`: `(0, 100]`, `[0, inf)`, `(-inf, inf)`. Finite ends are
/// numbers; an infinite end is open; the lower end lies below the upper one. The error
/// names the text and what is allowed.
pub fn parse(text: &str) -> Result<(End, End), String> {
    let t = text.trim();
    let why = |m: &str| format!("range `{text}`: {m}; write an interval such as \"(0, 100]\" or \"[0, inf)\"");
    let (Some(first), Some(last)) = (t.chars().next(), t.chars().last()) else { return Err(why("empty")) };
    let inner = t.get(1..t.len().saturating_sub(1)).filter(|_| t.len() >= 2).unwrap_or_default();
    let Some((a, b)) = inner.split_once(',') else { return Err(why("two ends separated by a comma")) };
    let end = |s: &str, open: bool, infinite: &[&str]| -> Result<End, String> {
        let s = s.trim();
        if infinite.contains(&s) {
            return if open { Ok(End::Unbounded) } else { Err(why("an infinite end is open")) };
        }
        match s.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(if open { End::Open(x) } else { End::Closed(x) }),
            _ => Err(why(&format!("`{s}` is not a finite number"))),
        }
    };
    let lo = match first {
        '(' => end(a, true, &["-inf"])?,
        '[' => end(a, false, &["-inf"])?,
        _ => return Err(why("it must start with ( or [")),
    };
    let hi = match last {
        ')' => end(b, true, &["inf", "+inf"])?,
        ']' => end(b, false, &["inf", "+inf"])?,
        _ => return Err(why("it must end with ) or ]")),
    };
    if lo.value(f64::NEG_INFINITY) >= hi.value(f64::INFINITY) {
        return Err(why("the lower end must be below the upper end"));
    }
    Ok((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_and_their_refusals() {
        assert_eq!(parse("(0, 100]"), Ok((End::Open(0.0), End::Closed(100.0))));
        assert_eq!(parse(" [1e-3,inf) "), Ok((End::Closed(1e-3), End::Unbounded)));
        assert_eq!(parse("(-inf, +inf)"), Ok((End::Unbounded, End::Unbounded)));
        for (bad, why) in [
            ("", "empty"),
            ("0, 1", "start with ("),
            ("(0, 1", "end with )"),
            ("(0; 1)", "comma"),
            ("[-inf, 0]", "infinite end is open"),
            ("(0, x)", "`x` is not a finite number"),
            ("(0, nan)", "not a finite number"),
            ("(1, 1]", "lower end must be below"),
        ] {
            let e = parse(bad).unwrap_err();
            assert!(e.contains(why) && e.contains(&format!("`{bad}`")), "{bad}: {e}");
        }
    }
}
