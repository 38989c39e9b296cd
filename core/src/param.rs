//! Parameters of closures: value, unit, valid range and meaning, in one place, so that
//! listing (`saltus models`), documentation and validation can never disagree.

use std::fmt;

/// One end of a [`ParamRange`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// value itself excluded
    Open(f64),
    /// value itself included
    Closed(f64),
    /// no limit
    Unbounded,
}

/// Valid interval of a real parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamRange {
    /// lower end
    pub lo: Bound,
    /// upper end
    pub hi: Bound,
}

impl ParamRange {
    /// `[lo, hi]`
    pub const fn closed(lo: f64, hi: f64) -> Self {
        Self { lo: Bound::Closed(lo), hi: Bound::Closed(hi) }
    }
    /// `(lo, hi)`
    pub const fn open(lo: f64, hi: f64) -> Self {
        Self { lo: Bound::Open(lo), hi: Bound::Open(hi) }
    }
    /// `(lo, hi]`
    pub const fn open_closed(lo: f64, hi: f64) -> Self {
        Self { lo: Bound::Open(lo), hi: Bound::Closed(hi) }
    }
    /// `[lo, hi)`
    pub const fn closed_open(lo: f64, hi: f64) -> Self {
        Self { lo: Bound::Closed(lo), hi: Bound::Open(hi) }
    }
    /// `(0, inf)`
    pub const fn positive() -> Self {
        Self { lo: Bound::Open(0.0), hi: Bound::Unbounded }
    }
    /// `[0, inf)`
    pub const fn non_negative() -> Self {
        Self { lo: Bound::Closed(0.0), hi: Bound::Unbounded }
    }
    /// any finite value
    pub const fn any() -> Self {
        Self { lo: Bound::Unbounded, hi: Bound::Unbounded }
    }

    /// Whether `x` is finite and inside the range.
    pub fn contains(&self, x: f64) -> bool {
        if !x.is_finite() {
            return false;
        }
        let lo_ok = match self.lo {
            Bound::Open(a) => x > a,
            Bound::Closed(a) => x >= a,
            Bound::Unbounded => true,
        };
        let hi_ok = match self.hi {
            Bound::Open(b) => x < b,
            Bound::Closed(b) => x <= b,
            Bound::Unbounded => true,
        };
        lo_ok && hi_ok
    }
}

impl std::str::FromStr for ParamRange {
    type Err = String;

    /// An interval as [`ParamRange`] displays it: `(0, 100]`, `[0, inf)`, `(-inf, inf)`
    /// (an infinite end is open). The same grammar as the `range` attribute of
    /// `#[derive(Describe)]`, read at run time (a closure registered from Python).
    fn from_str(text: &str) -> Result<Self, String> {
        let bound = |e| match e {
            saltus_interval::End::Unbounded => Bound::Unbounded,
            saltus_interval::End::Open(x) => Bound::Open(x),
            saltus_interval::End::Closed(x) => Bound::Closed(x),
        };
        let (lo, hi) = saltus_interval::parse(text)?;
        Ok(ParamRange { lo: bound(lo), hi: bound(hi) })
    }
}

/// A number as a reader wants it in a message: plain between 1e-4 and 1e6, in
/// exponent notation outside (1e-308 and f64::MAX would otherwise print with over 300
/// digits), `NaN` and `inf` as such.
pub fn number(x: f64) -> String {
    // ten significant digits: a bound computed as 2 (1 + skin) d prints as 0.0132, not as
    // 0.013200000000000002
    // (f64::MAX rounds up past the largest double: it keeps its digits)
    let x = format!("{x:.9e}").parse::<f64>().ok().filter(|r| r.is_finite() || !x.is_finite()).unwrap_or(x);
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A time or a height for a message: six decimals from 0.1 up (and for exactly 0), six
/// significant digits below, where six decimals would print an early instability at
/// t = 1e-7 s as `0.000000`.
pub fn decimal(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || x.abs() >= 0.1 {
        format!("{x:.6}")
    } else {
        format!("{x:.5e}")
    }
}

impl fmt::Display for ParamRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.lo {
            Bound::Open(a) => write!(f, "({}, ", number(a))?,
            Bound::Closed(a) => write!(f, "[{}, ", number(a))?,
            Bound::Unbounded => write!(f, "(-inf, ")?,
        }
        match self.hi {
            Bound::Open(b) => write!(f, "{})", number(b)),
            Bound::Closed(b) => write!(f, "{}]", number(b)),
            Bound::Unbounded => write!(f, "inf)"),
        }
    }
}

/// A real parameter of a closure with its current value.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// key in the closure's TOML table (dotted for nested tables, e.g. `g0.a`)
    pub name: String,
    /// current value (the default when listed from a default instance)
    pub value: f64,
    /// valid range
    pub range: ParamRange,
    /// SI unit, `-` when dimensionless
    pub unit: &'static str,
    /// meaning, one line
    pub doc: &'static str,
}

impl Param {
    /// Shorthand constructor.
    pub fn new(name: impl Into<String>, value: f64, range: ParamRange, unit: &'static str, doc: &'static str) -> Self {
        Self { name: name.into(), value, range, unit, doc }
    }

    /// Same parameter with its key prefixed by `prefix.` (nested tables).
    pub fn prefixed(mut self, prefix: &str) -> Self {
        self.name = format!("{prefix}.{}", self.name);
        self
    }
}

/// A parameter value that breaks its range or a cross-parameter constraint.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("`{key}` = {value}: allowed {allowed}")]
pub struct ParamError {
    /// key relative to the closure table
    pub key: String,
    /// offending value, formatted
    pub value: String,
    /// what is allowed, e.g. `(0, 1]` or `< phi_max (0.635)`
    pub allowed: String,
}

impl ParamError {
    /// Error for key `key` whose value `value` is not within `allowed`.
    pub fn new(key: impl Into<String>, value: f64, allowed: impl Into<String>) -> Self {
        Self { key: key.into(), value: number(value), allowed: allowed.into() }
    }
}

/// A parameter chosen among named values: a string option (`form = "prandtl"`), a switch
/// (`enabled = true`) or the `type` of a sub-table (`g0.type`).
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// key in the closure's TOML table (dotted for nested tables)
    pub name: String,
    /// current value as written in TOML (without quotes)
    pub value: String,
    /// every accepted value
    pub allowed: Vec<&'static str>,
    /// meaning, one line
    pub doc: &'static str,
}

/// What a closure lists about itself: real parameters and choices, in field order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParamSet {
    /// real parameters
    pub params: Vec<Param>,
    /// string options and switches
    pub choices: Vec<Choice>,
}

/// `prefix.key`, or `key` at the top level (`prefix` empty).
pub fn join_key(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// How a field that is not a plain `f64` describes itself inside a closure's listing.
///
/// `#[derive(Params)]` implements it for sub-table structs, string-option enums and
/// tagged enums of sub-tables; `#[derive(Describe)]` calls it for every such field.
pub trait DescribeField {
    /// Add this field's parameters and choices to `out`, keyed under `prefix` (the
    /// field's dotted key); `doc` is the field's own description.
    fn describe_field(&self, prefix: &str, doc: &'static str, out: &mut ParamSet);
}

impl DescribeField for bool {
    fn describe_field(&self, prefix: &str, doc: &'static str, out: &mut ParamSet) {
        out.choices.push(Choice {
            name: prefix.to_string(),
            value: self.to_string(),
            allowed: vec!["true", "false"],
            doc,
        });
    }
}

impl<T: DescribeField> DescribeField for Option<T> {
    fn describe_field(&self, prefix: &str, doc: &'static str, out: &mut ParamSet) {
        if let Some(v) = self {
            v.describe_field(prefix, doc, out);
        }
    }
}

/// A property a model declares about its main output, verified by `saltus closure check`
/// (see `saltus::check`). The main output and input of each family: drag, C_D(Re_p);
/// hindrance, f(phi) at every Re_p; viscosity, nu_eff/nu_f(phi); local granular
/// rheology, mu(I or K); kinetic theory, g0(phi); algebraic turbulence, l_m(z) in clear
/// fluid; fluctuation, the diffusivity D. A limit declared on a family it does not apply
/// to fails the check.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Limit {
    /// drag: C_D Re_p tends to `cd_re` as Re_p -> 0 (24: Stokes 1851)
    Stokes {
        /// limit of C_D Re_p
        cd_re: f64,
    },
    /// drag: C_D tends to `DragLaw::cd_inf()` as Re_p -> inf
    HighReynolds,
    /// hindrance, viscosity: the factor tends to 1 as phi -> 0
    Dilute,
    /// viscosity: nu_eff/nu_f = 1 + `coefficient` phi + O(phi^2) as phi -> 0
    /// (5/2: Einstein 1906)
    Einstein {
        /// first-order coefficient
        coefficient: f64,
    },
    /// the main output does not increase with the main input
    Decreasing,
    /// the main output does not decrease with the main input
    Increasing,
    /// local granular rheology: mu tends to `mu_s` as the control number I (or K) -> 0,
    /// the quasi-static friction of mu(I) (Jop, Forterre & Pouliquen 2006 eq 5;
    /// Chassagne et al. 2023 eq 1.1)
    StaticFriction {
        /// limit of mu
        mu_s: f64,
    },
    /// local granular rheology: the packing phi does not increase with the control
    /// number (dilatancy, Chassagne et al. 2023 eq 1.2); the solver's bisection of the
    /// packing inverse relies on it
    PackingDecreasing,
    /// algebraic turbulence: l_m / z tends to `kappa` as z -> 0 in clear fluid, the law
    /// of the wall l_m = kappa z (Prandtl; Chassagne et al. 2023 eq 2.8b without grains)
    WallLength {
        /// von Karman constant
        kappa: f64,
    },
    /// fluctuation: the particle diffusivity D >= 0 (a negative D makes the drift flux
    /// of Chassagne et al. 2023 eq 4.4 anti-diffusive)
    NonNegative,
}

/// Self-description shared by every closure: name, source, parameters, validation.
///
/// Derive it: `#[derive(Describe)]` with `#[describe(name, source, equation)]` on the
/// struct and `#[param(range, unit)]` on its real parameters (see the `saltus_derive`
/// crate documentation); write it by hand only for what the attributes cannot say.
///
/// `validate` has a default that checks every [`Param`] against its range, then calls
/// [`Describe::check_constraints`] for relations between parameters.
pub trait Describe {
    /// Registered model name (the `type` of its TOML table).
    fn name(&self) -> &'static str;
    /// Paper and equation numbers.
    fn source(&self) -> &'static str;
    /// The equation, one line, plain text.
    fn equation(&self) -> &'static str;
    /// Real parameters with their current values and ranges.
    fn params(&self) -> Vec<Param> {
        Vec::new()
    }
    /// String options and switches with their allowed values.
    fn choices(&self) -> Vec<Choice> {
        Vec::new()
    }
    /// Limits and monotonicity the model declares (checked by `saltus closure check`).
    fn limits(&self) -> Vec<Limit> {
        Vec::new()
    }
    /// Constraints linking several parameters (e.g. `phi_rlp < phi_max`).
    fn check_constraints(&self) -> Result<(), ParamError> {
        Ok(())
    }
    /// The first error met while evaluating, which the `f64` methods of the family traits
    /// cannot return: a closure registered at run time whose function raised (it then
    /// returns NaN, and the run driver stops the run with this message). `None` for
    /// compiled closures.
    fn failure(&self) -> Option<String> {
        None
    }
    /// Check every parameter; the first violation is returned.
    fn validate(&self) -> Result<(), ParamError> {
        for p in self.params() {
            if !p.range.contains(p.value) {
                return Err(ParamError::new(p.name, p.value, p.range.to_string()));
            }
        }
        self.check_constraints()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extreme_numbers_print_short() {
        assert_eq!(number(1e-308), "1e-308");
        assert_eq!(number(f64::MAX), "1.7976931348623157e308");
        assert_eq!(number(0.05), "0.05");
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(ParamRange::closed(1e-7, f64::MAX).to_string(), "[1e-7, 1.7976931348623157e308]");
        assert_eq!(number(2.0 * 0.006 * 1.1), "0.0132");
        assert_eq!(number(f64::INFINITY), "inf");
    }

    #[test]
    fn small_times_keep_their_digits() {
        assert_eq!(decimal(0.0), "0.000000");
        assert_eq!(decimal(3.0), "3.000000");
        assert_eq!(decimal(7.29e-8), "7.29000e-8");
    }

    #[test]
    fn ranges_read_back_from_their_display() {
        for r in [
            ParamRange::open_closed(0.0, 100.0),
            ParamRange::closed(-1.5, 2.0),
            ParamRange::non_negative(),
            ParamRange::any(),
            ParamRange::closed_open(1e-7, 0.6),
        ] {
            assert_eq!(r.to_string().parse::<ParamRange>(), Ok(r));
        }
        for bad in ["", "[1, 0]", "(0 1)", "[0, inf]", "0, 1", "[a, 1]", "[0, 1"] {
            let e = bad.parse::<ParamRange>().unwrap_err();
            assert!(e.starts_with(&format!("range `{bad}`")), "{e}");
        }
    }

    #[test]
    fn range_contains_and_display() {
        let r = ParamRange::open_closed(0.0, 1.0);
        assert!(!r.contains(0.0));
        assert!(r.contains(1.0));
        assert!(!r.contains(f64::NAN));
        assert_eq!(r.to_string(), "(0, 1]");
        assert!(ParamRange::positive().contains(1e30));
        assert!(!ParamRange::positive().contains(f64::INFINITY));
    }
}
