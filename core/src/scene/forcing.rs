//! `[physics.forcing]`: a driving that varies in time, added to the steady
//! `physics.pressure_gradient` (which is its mean when the signal has none).
//!
//! The signal is either the pressure gradient -dp/dx itself (`of = "pressure_gradient"`,
//! Pa/m) or a free-stream velocity U(t) (`of = "velocity"`, m/s, the default). Far from
//! the bed an oscillatory boundary layer is inviscid, rho_f dU/dt = -dp/dx (the outer
//! limit of the boundary-layer momentum equation; Schlichting & Gersten, Boundary-Layer
//! Theory, 2017, eq 15.5 for the oscillating outer flow; Fredsoe & Deigaard 1992 eq 2.2):
//! a velocity signal drives the column by G(t) = rho_f dU/dt, with the derivative taken
//! analytically. The velocity is then U(t) above the layer only if the mean flow is zero
//! at t = 0 (a column at rest follows U(t) - U(0)).
//!
//! Signals (`type`), with omega = 2 pi / period:
//!
//! * `constant`: `value`;
//! * `sinusoids`: `mean` + sum_n `amplitudes[n]` sin(n omega t + `phases[n]`), n = 1, 2, ...
//!   (harmonics of the period; phases in radians, zero when absent);
//! * `stokes2`: second-order Stokes velocity skewness in the form of O'Donoghue & Wright
//!   (2004, eq 1), U(t) = `u1` sin(omega t) - `u2` cos(2 omega t);
//! * `abreu2010`: the velocity- and acceleration-skewed wave of Abreu, Silva, Sancho &
//!   Temperville (2010, eq 7), U(t) = `amplitude` f [sin(omega t) + r sin(phi) / (1 +
//!   sqrt(1 - r^2))] / [1 - r cos(omega t + phi)] with f = sqrt(1 - r^2), the skewness
//!   index `r` in [0, 1) and the waveform parameter `phi` (radians; -pi/2 a purely
//!   acceleration-skewed wave, 0 a purely velocity-skewed one);
//! * `table`: a CSV `file` (relative to the scene) of two columns, time (s) and value,
//!   times strictly increasing, interpolated linearly (a velocity table drives by the
//!   slope of each segment); with `period`, repeated with that period (times within
//!   [0, period], the last point joined to the first one period later), else held at its
//!   end values.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// What the signal of a [`Forcing`] is.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// a free-stream velocity U(t) (m/s), driving by rho_f dU/dt
    #[default]
    Velocity,
    /// the pressure gradient -dp/dx (Pa/m) itself
    PressureGradient,
}

/// The signal of a [`Forcing`] (`type = "..."`).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Signal {
    /// a constant
    Constant {
        /// the value
        value: f64,
    },
    /// a mean and harmonics of one period
    Sinusoids {
        /// period of the first harmonic (s)
        period: f64,
        /// mean
        #[serde(default)]
        mean: f64,
        /// amplitude of harmonic n = 1, 2, ...
        amplitudes: Vec<f64>,
        /// phase of harmonic n (rad); zero when absent
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        phases: Vec<f64>,
    },
    /// second-order Stokes skewness, u1 sin(omega t) - u2 cos(2 omega t)
    Stokes2 {
        /// period (s)
        period: f64,
        /// first-harmonic amplitude
        u1: f64,
        /// second-harmonic amplitude
        u2: f64,
    },
    /// Abreu et al. 2010 eq 7
    Abreu2010 {
        /// period (s)
        period: f64,
        /// amplitude U_w
        amplitude: f64,
        /// skewness index r in [0, 1)
        r: f64,
        /// waveform parameter phi (rad)
        phi: f64,
    },
    /// a CSV time series
    Table {
        /// two-column CSV (time, value), relative to the scene; absolute once loaded
        file: String,
        /// repeat with this period (s); held at the end values when absent
        #[serde(default, skip_serializing_if = "Option::is_none")]
        period: Option<f64>,
        /// rows read from `file`
        #[serde(skip)]
        rows: Vec<(f64, f64)>,
    },
}

/// `[physics.forcing]`: a signal and what it is.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Forcing {
    /// the velocity U(t) or the pressure gradient -dp/dx
    pub of: Quantity,
    /// the signal
    #[serde(flatten)]
    pub signal: Signal,
}

/// Most harmonics of `sinusoids` and rows of a `table`.
const MAX_HARMONICS: usize = 1000;
const MAX_ROWS: usize = 10_000_000;

impl Forcing {
    /// Read `[physics.forcing]` of `file` (the value at key `physics.forcing`), reading a
    /// table's CSV relative to the scene's folder; every error names the file and key.
    pub fn from_value(value: toml::Value, file: &Path) -> Result<Forcing> {
        const KEY: &str = "physics.forcing";
        let key_error = |key: &str, message: String| Error::Key { file: file.into(), key: key.into(), message };
        let toml::Value::Table(mut table) = value else {
            return Err(key_error(KEY, "expected a table ([physics.forcing])".into()));
        };
        let of = match table.remove("of") {
            None => Quantity::default(),
            Some(v) => super::de_path(v, file, "physics.forcing.of")?,
        };
        if !table.contains_key("type") {
            return Err(key_error(
                "physics.forcing.type",
                "missing; one of \"constant\", \"sinusoids\", \"stokes2\", \"abreu2010\", \"table\"".into(),
            ));
        }
        let mut signal: Signal = super::de_path(toml::Value::Table(table), file, KEY)?;
        let finite = |k: &str, v: f64| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(key_error(&format!("{KEY}.{k}"), format!("= {v}: must be a finite number")))
            }
        };
        let period_ok = |k: &str, t: f64| {
            if t.is_finite() && t > 0.0 && t <= super::MAX_TIME {
                Ok(())
            } else {
                Err(key_error(&format!("{KEY}.{k}"), format!("= {t}: a period in (0, {:e}] s", super::MAX_TIME)))
            }
        };
        match &mut signal {
            Signal::Constant { value } => finite("value", *value)?,
            Signal::Sinusoids { period, mean, amplitudes, phases } => {
                period_ok("period", *period)?;
                finite("mean", *mean)?;
                if amplitudes.is_empty() || amplitudes.len() > MAX_HARMONICS {
                    return Err(key_error(
                        &format!("{KEY}.amplitudes"),
                        format!("{} amplitudes: give 1 to {MAX_HARMONICS}, one per harmonic", amplitudes.len()),
                    ));
                }
                if !phases.is_empty() && phases.len() != amplitudes.len() {
                    return Err(key_error(
                        &format!("{KEY}.phases"),
                        format!(
                            "{} phases for {} amplitudes: give one per amplitude, or none",
                            phases.len(),
                            amplitudes.len()
                        ),
                    ));
                }
                for (i, &a) in amplitudes.iter().enumerate() {
                    finite(&format!("amplitudes[{i}]"), a)?;
                }
                for (i, &p) in phases.iter().enumerate() {
                    finite(&format!("phases[{i}]"), p)?;
                }
            }
            Signal::Stokes2 { period, u1, u2 } => {
                period_ok("period", *period)?;
                finite("u1", *u1)?;
                finite("u2", *u2)?;
            }
            Signal::Abreu2010 { period, amplitude, r, phi } => {
                period_ok("period", *period)?;
                finite("amplitude", *amplitude)?;
                finite("phi", *phi)?;
                if !(r.is_finite() && (0.0..1.0).contains(r)) {
                    return Err(key_error(&format!("{KEY}.r"), format!("= {r}: the skewness index is in [0, 1)")));
                }
            }
            Signal::Table { file: csv, period, rows } => {
                if let Some(t) = period {
                    period_ok("period", *t)?;
                }
                let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
                *csv = super::absolute(&dir, csv);
                *rows = read_rows(Path::new(csv.as_str()), file)?;
                if let (Some(t), Some(first), Some(last)) = (*period, rows.first(), rows.last()) {
                    if first.0 < 0.0 || last.0 > t {
                        return Err(key_error(
                            &format!("{KEY}.file"),
                            format!(
                                "{csv}: times from {} to {} s; with period = {t} s they must lie within [0, {t}]",
                                first.0, last.0
                            ),
                        ));
                    }
                    if last.0 - first.0 >= t {
                        return Err(key_error(
                            &format!("{KEY}.file"),
                            format!("{csv}: the first and last times are a whole period apart; drop the last row, the period repeats the first"),
                        ));
                    }
                }
            }
        }
        Ok(Forcing { of, signal })
    }

    /// Whether the signal changes in time (everything but `constant`).
    pub fn is_unsteady(&self) -> bool {
        !matches!(self.signal, Signal::Constant { .. })
    }

    /// The period of a periodic signal (s); `None` for a constant or a table without one.
    pub fn period(&self) -> Option<f64> {
        match &self.signal {
            Signal::Constant { .. } => None,
            Signal::Sinusoids { period, .. } | Signal::Stokes2 { period, .. } | Signal::Abreu2010 { period, .. } => {
                Some(*period)
            }
            Signal::Table { period, .. } => *period,
        }
    }

    /// The signal at time `t` (s) and its time derivative.
    pub fn value_and_rate(&self, t: f64) -> (f64, f64) {
        use std::f64::consts::TAU;
        match &self.signal {
            Signal::Constant { value } => (*value, 0.0),
            Signal::Sinusoids { period, mean, amplitudes, phases } => {
                let w = TAU / period;
                let (mut v, mut r) = (*mean, 0.0);
                for (n, &a) in amplitudes.iter().enumerate() {
                    let k = (n + 1) as f64 * w;
                    let arg = k * t + phases.get(n).copied().unwrap_or(0.0);
                    v += a * arg.sin();
                    r += a * k * arg.cos();
                }
                (v, r)
            }
            Signal::Stokes2 { period, u1, u2 } => {
                let w = TAU / period;
                let wt = w * t;
                (u1 * wt.sin() - u2 * (2.0 * wt).cos(), w * (u1 * wt.cos() + 2.0 * u2 * (2.0 * wt).sin()))
            }
            Signal::Abreu2010 { period, amplitude, r, phi } => {
                let w = TAU / period;
                let wt = w * t;
                let f = (1.0 - r * r).sqrt();
                let c = r * phi.sin() / (1.0 + f);
                let num = wt.sin() + c;
                let den = 1.0 - r * (wt + phi).cos();
                let v = amplitude * f * num / den;
                let rate = amplitude * f * w * (wt.cos() * den - num * r * (wt + phi).sin()) / (den * den);
                (v, rate)
            }
            Signal::Table { rows, period, .. } => table_at(rows, *period, t),
        }
    }

    /// The pressure gradient -dp/dx it adds at time `t` (Pa/m) in a fluid of density
    /// `rho_f`: the signal, or rho_f dU/dt of a velocity.
    pub fn gradient(&self, t: f64, rho_f: f64) -> f64 {
        let (v, rate) = self.value_and_rate(t);
        match self.of {
            Quantity::PressureGradient => v,
            Quantity::Velocity => rho_f * rate,
        }
    }
}

/// Linear interpolation of `rows` at `t` with its slope: periodic with `period`, else held
/// at the end values (slope 0 outside).
fn table_at(rows: &[(f64, f64)], period: Option<f64>, t: f64) -> (f64, f64) {
    let (Some(&first), Some(&last)) = (rows.first(), rows.last()) else { return (0.0, 0.0) };
    let segment = |a: (f64, f64), b: (f64, f64), t: f64| {
        let slope = (b.1 - a.1) / (b.0 - a.0);
        (a.1 + slope * (t - a.0), slope)
    };
    let t = match period {
        Some(p) => {
            let mut s = t.rem_euclid(p);
            if s < first.0 {
                s += p;
            }
            if s >= last.0 {
                // the wrap from the last row to the first one a period later
                return segment(last, (first.0 + p, first.1), s);
            }
            s
        }
        None => {
            if t <= first.0 {
                return (first.1, 0.0);
            }
            if t >= last.0 {
                return (last.1, 0.0);
            }
            t
        }
    };
    // the segment [rows[i-1], rows[i]] holding t
    let i = rows.partition_point(|r| r.0 <= t).clamp(1, rows.len() - 1);
    segment(rows[i - 1], rows[i], t)
}

/// The (time, value) rows of a forcing table: comma- or whitespace-separated, `#` comments
/// and one header line allowed, at least two rows, times strictly increasing, every value
/// finite.
fn read_rows(csv: &Path, scene: &Path) -> Result<Vec<(f64, f64)>> {
    let key = "physics.forcing.file";
    let err = |message: String| Error::Key { file: scene.into(), key: key.into(), message };
    let text = std::fs::read_to_string(csv).map_err(|e| err(format!("{}: {e}", csv.display())))?;
    let mut rows: Vec<(f64, f64)> = Vec::new();
    let mut header_seen = false;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).collect();
        let numbers: Vec<Option<f64>> = fields.iter().map(|s| s.parse::<f64>().ok()).collect();
        if rows.is_empty() && !header_seen && numbers.iter().any(Option::is_none) {
            header_seen = true;
            continue;
        }
        let at = format!("{} line {}", csv.display(), n + 1);
        let (t, v) = match numbers.as_slice() {
            [Some(t), Some(v)] => (*t, *v),
            _ => return Err(err(format!("{at}: expected two numbers (time, value), found `{line}`"))),
        };
        if !(t.is_finite() && v.is_finite()) {
            return Err(err(format!("{at}: non-finite number in `{line}`")));
        }
        if let Some(&(prev, _)) = rows.last() {
            if t <= prev {
                return Err(err(format!("{at}: time {t} s after {prev} s; times must increase strictly")));
            }
        }
        if rows.len() == MAX_ROWS {
            return Err(err(format!("{}: more than {MAX_ROWS} rows", csv.display())));
        }
        rows.push((t, v));
    }
    if rows.len() < 2 {
        return Err(err(format!(
            "{}: {} rows; a table needs at least two (time, value) rows",
            csv.display(),
            rows.len()
        )));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn forcing(text: &str) -> Result<Forcing> {
        let v: toml::Table = toml::from_str(text).expect("toml");
        Forcing::from_value(toml::Value::Table(v), Path::new("scene.toml"))
    }

    /// The analytic derivatives against central differences of the values.
    #[test]
    fn rates_are_the_derivatives_of_the_signals() {
        for text in [
            "type = \"sinusoids\"\nperiod = 2.0\nmean = 0.3\namplitudes = [1.0, 0.4]\nphases = [0.1, -1.0]",
            "type = \"stokes2\"\nperiod = 5.0\nu1 = 1.2\nu2 = 0.3",
            "type = \"abreu2010\"\nperiod = 5.0\namplitude = 1.5\nr = 0.6\nphi = -1.5707963267948966",
            "type = \"abreu2010\"\nperiod = 7.0\namplitude = 1.0\nr = 0.3\nphi = 0.4",
        ] {
            let f = forcing(text).unwrap();
            for k in 0..40 {
                let t = 0.173 * k as f64;
                let h = 1e-5;
                let fd = (f.value_and_rate(t + h).0 - f.value_and_rate(t - h).0) / (2.0 * h);
                let (_, rate) = f.value_and_rate(t);
                assert!((fd - rate).abs() < 1e-6 * (1.0 + rate.abs()), "{text} at {t}: {rate} vs {fd}");
            }
            // periodic
            let p = f.period().unwrap();
            let (a, b) = (f.value_and_rate(0.37).0, f.value_and_rate(0.37 + 3.0 * p).0);
            assert!((a - b).abs() < 1e-9, "{text}");
        }
    }

    /// Abreu et al.'s waveform: r = 0 is the sinusoid of amplitude U_w; its velocity is
    /// zero-mean for any r and phi (their eq 7 is built so).
    #[test]
    fn abreu_limits() {
        let f = forcing("type = \"abreu2010\"\nperiod = 4.0\namplitude = 1.3\nr = 0.0\nphi = 0.7").unwrap();
        for k in 0..50 {
            let t = 0.09 * k as f64;
            let exact = 1.3 * (std::f64::consts::TAU * t / 4.0).sin();
            assert!((f.value_and_rate(t).0 - exact).abs() < 1e-12);
        }
        let f = forcing("type = \"abreu2010\"\nperiod = 1.0\namplitude = 1.0\nr = 0.5\nphi = -0.8").unwrap();
        let n = 100_000;
        let mean: f64 = (0..n).map(|k| f.value_and_rate((k as f64 + 0.5) / n as f64).0).sum::<f64>() / n as f64;
        assert!(mean.abs() < 1e-9, "mean {mean}");
    }

    #[test]
    fn a_velocity_drives_by_its_acceleration() {
        let f = forcing("type = \"stokes2\"\nperiod = 5.0\nu1 = 1.0\nu2 = 0.0").unwrap();
        let w = std::f64::consts::TAU / 5.0;
        assert!((f.gradient(0.0, 1000.0) - 1000.0 * w).abs() < 1e-9);
        let g = forcing("of = \"pressure_gradient\"\ntype = \"constant\"\nvalue = 3.5").unwrap();
        assert_eq!(g.gradient(12.0, 1000.0), 3.5);
        assert!(!g.is_unsteady() && f.is_unsteady());
    }

    #[test]
    fn tables_interpolate_hold_and_repeat() {
        let rows = vec![(0.0, 0.0), (1.0, 2.0), (3.0, -2.0)];
        assert_eq!(table_at(&rows, None, 0.5), (1.0, 2.0));
        assert_eq!(table_at(&rows, None, 2.0), (0.0, -2.0));
        assert_eq!(table_at(&rows, None, -1.0), (0.0, 0.0));
        assert_eq!(table_at(&rows, None, 5.0), (-2.0, 0.0));
        // period 4: the last row joins the first at t = 4
        assert_eq!(table_at(&rows, Some(4.0), 4.5), (1.0, 2.0));
        assert_eq!(table_at(&rows, Some(4.0), 3.5), (-1.0, 2.0));
    }

    #[test]
    fn bad_forcings_are_refused_with_their_key() {
        let key = |text: &str| match forcing(text) {
            Err(Error::Key { key, message, .. }) => format!("{key}: {message}"),
            Err(e) => panic!("{e}"),
            Ok(_) => panic!("accepted: {text}"),
        };
        let e = key("type = \"square\"\nperiod = 1.0");
        assert!(e.starts_with("physics.forcing") && e.contains("square"), "{e}");
        assert!(key("period = 1.0").starts_with("physics.forcing.type: missing"));
        assert!(key("type = \"stokes2\"\nperiod = -1.0\nu1 = 1.0\nu2 = 0.0").starts_with("physics.forcing.period"));
        assert!(key("type = \"stokes2\"\nperiod = 1.0\nu1 = nan\nu2 = 0.0").starts_with("physics.forcing.u1"));
        assert!(key("type = \"abreu2010\"\nperiod = 1.0\namplitude = 1.0\nr = 1.0\nphi = 0.0")
            .starts_with("physics.forcing.r"));
        assert!(key("type = \"sinusoids\"\nperiod = 1.0\namplitudes = []").starts_with("physics.forcing.amplitudes"));
        assert!(key("type = \"sinusoids\"\nperiod = 1.0\namplitudes = [1.0]\nphases = [0.0, 1.0]")
            .starts_with("physics.forcing.phases"));
        assert!(key("type = \"constant\"\nvalue = 1.0\nextra = 2").contains("extra"));
        assert!(key("of = \"acceleration\"\ntype = \"constant\"\nvalue = 1.0").starts_with("physics.forcing.of"));
        assert!(key("type = \"table\"\nfile = \"/nonexistent/forcing.csv\"").starts_with("physics.forcing.file"));
        let dir = std::env::temp_dir().join(format!("saltus-forcing-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let write = |name: &str, text: &str| {
            let p = dir.join(name);
            std::fs::write(&p, text).unwrap();
            format!("type = \"table\"\nfile = \"{}\"", p.display())
        };
        let e = key(&write("empty.csv", "t,u\n"));
        assert!(e.starts_with("physics.forcing.file") && e.contains("0 rows"), "{e}");
        let e = key(&write("back.csv", "t,u\n0,0\n1,1\n0.5,2\n"));
        assert!(e.contains("increase strictly"), "{e}");
        let e = key(&write("inf.csv", "0,0\n1,inf\n"));
        assert!(e.contains("non-finite"), "{e}");
        let ok = forcing(&write("ok.csv", "# U(t)\ntime,u\n0,0\n1,1\n")).unwrap();
        assert_eq!(ok.value_and_rate(0.25), (0.25, 1.0));
        let e = key(&(write("long.csv", "0,0\n2,1\n") + "\nperiod = 1.0"));
        assert!(e.contains("within [0, 1]"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
