//! Scene fuzzer: mutates the shipped scenes one key at a time with extreme values and runs
//! `saltus check` and a short `saltus run` of each mutant, reporting what the project's
//! rules forbid: a panic or an abort (exit 101, a signal), a hang (past the timeout), a
//! run that writes a non-finite number, a `check`/`run` disagreement (check accepts,
//! run refuses the scene), and an unexpected exit code.
//!
//! ```text
//! cargo build --release
//! cargo run --release --example fuzz_scenes -- [--minutes 20] [--timeout 20] [--out DIR] [SCENE...]
//! ```
//!
//! Keys are the leaves of each scene as `check` resolves it (every default filled in), plus
//! one unknown key per table. Values: 0, -1, 1e-308, 1e308, nan, inf, -inf, a string, a
//! table. A mutant that `check` accepts is run with the solvers' step caps lowered (unless
//! the mutated key is one of them, whose run may then legitimately outlast the timeout),
//! so that a run is short but still reaches the deposition and the first flow steps. Findings are printed and written to
//! `DIR/findings.txt`; the counts close the output.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const VALUES: [&str; 9] = ["0", "-1", "1e-308", "1e308", "nan", "inf", "-inf", "\"x\"", "{a=1}"];

const DEFAULT_SCENES: [&str; 9] = [
    "cases/chassagne2023/case01.toml",
    "cases/verification/couette_laminar.toml",
    "cases/revil_baudard2015/sheet_flow_k_omega_kinetic.toml",
    "cases/revil_baudard2015/fixed_bed_k_omega.toml",
    "cases/fry2024/couette_bedload.toml",
    "cases/verification/dem_binary_collision.toml",
    "cases/verification/dem_homogeneous_cooling.toml",
    "cases/maurin2015/frey_sim6.toml",
    "cases/chassagne2023/case13.toml",
];

/// Keys that bound the short runs; a mutant of one of them runs without the caps.
/// Step caps only: a lowered end time could fall before `stats_start` and make `run`
/// refuse what `check` accepted.
const CAPS: [(&str, &str); 2] = [("solver.eulerian.max_steps", "300"), ("solver.lagrangian.max_steps", "3000")];

struct Outcome {
    code: Option<i32>,
    timed_out: bool,
    stdout: String,
    stderr: String,
}

fn run(bin: &Path, args: &[String], timeout: Duration) -> Outcome {
    let child = Command::new(bin).args(args).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => return Outcome { code: None, timed_out: false, stdout: String::new(), stderr: e.to_string() },
    };
    // drain the pipes in threads so that a chatty child cannot block on a full pipe
    let mut out = child.stdout.take();
    let mut err = child.stderr.take();
    let t_out = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(o) = out.as_mut() {
            let _ = std::io::Read::read_to_string(o, &mut s);
        }
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(e) = err.as_mut() {
            let _ = std::io::Read::read_to_string(e, &mut s);
        }
        s
    });
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if start.elapsed() > timeout => {
                timed_out = true;
                let _ = child.kill();
                break child.wait().ok();
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(_) => break None,
        }
    };
    let code = status.and_then(|s| s.code());
    Outcome { code, timed_out, stdout: t_out.join().unwrap_or_default(), stderr: t_err.join().unwrap_or_default() }
}

/// Dotted leaf keys of a TOML table, and one unknown key per table.
fn keys(prefix: &str, t: &toml::Table, out: &mut Vec<String>) {
    out.push(format!("{prefix}fuzz_unknown_key"));
    for (k, v) in t {
        let path = format!("{prefix}{k}");
        match v {
            toml::Value::Table(inner) => keys(&format!("{path}."), inner, out),
            // arrays (particle lists, reference tables) are mutated whole
            _ => out.push(path),
        }
    }
}

/// First non-finite number written into `dir`'s outputs, if any.
fn non_finite(dir: &Path) -> Option<String> {
    // serde_json writes a non-finite f64 as null; a CSV cell as NaN or inf
    let bad = |f: &str, line: &str| {
        let l = line.to_ascii_lowercase();
        if f.ends_with(".json") {
            l.trim_end_matches(',').ends_with(": null")
        } else {
            l.split(',').any(|c| c.contains("nan") || c.contains("inf"))
        }
    };
    for f in ["profiles.csv", "summary.json"] {
        let Ok(text) = std::fs::read_to_string(dir.join(f)) else { continue };
        for (n, line) in text.lines().enumerate() {
            if bad(f, line) {
                return Some(format!("{f}:{}: {line}", n + 1));
            }
        }
    }
    None
}

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut minutes, mut timeout, mut out, mut scenes) = (20.0f64, 20.0f64, PathBuf::from("target/fuzz"), Vec::new());
    while let Some(a) = args.next() {
        match a.as_str() {
            "--minutes" => minutes = args.next().and_then(|v| v.parse().ok()).unwrap_or(minutes),
            "--timeout" => timeout = args.next().and_then(|v| v.parse().ok()).unwrap_or(timeout),
            "--out" => out = args.next().map(PathBuf::from).unwrap_or(out),
            _ => scenes.push(a),
        }
    }
    if scenes.is_empty() {
        scenes = DEFAULT_SCENES.iter().map(|s| s.to_string()).collect();
    }
    let bin = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/release/saltus");
    let deadline = Instant::now() + Duration::from_secs_f64(minutes * 60.0);
    let timeout = Duration::from_secs_f64(timeout);
    let _ = std::fs::create_dir_all(&out);
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    let mut findings = Vec::new();
    // interleave the scenes: every scene gets keys before the deadline
    let mut plans = Vec::new();
    for scene in &scenes {
        let o = run(&bin, &["check".into(), scene.clone()], timeout);
        let Ok(table) =
            o.stdout.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n").parse::<toml::Table>()
        else {
            eprintln!("{scene}: resolved scene not readable, skipped");
            continue;
        };
        let mut k = Vec::new();
        keys("", &table, &mut k);
        plans.push((scene.clone(), k));
    }
    let longest = plans.iter().map(|p| p.1.len()).max().unwrap_or(0);
    'outer: for i in 0..longest {
        for (scene, keys) in &plans {
            let Some(key) = keys.get(i) else { continue };
            for value in VALUES {
                if Instant::now() > deadline {
                    break 'outer;
                }
                let set = format!("{key}={value}");
                let label = format!("{scene} --set '{set}'");
                *counts.entry("mutants").or_default() += 1;
                let check = run(&bin, &["check".into(), scene.clone(), "--set".into(), set.clone()], timeout);
                macro_rules! report {
                    ($kind:expr, $what:expr) => {{
                        let kind: &'static str = $kind;
                        *counts.entry(kind).or_default() += 1;
                        let line = format!("{kind}: {label}: {}", $what);
                        println!("{line}");
                        findings.push(line);
                    }};
                }
                if check.timed_out {
                    report!("hang", "check");
                    continue;
                }
                if check.stderr.contains("panicked") || !matches!(check.code, Some(0) | Some(2)) {
                    report!(
                        "crash",
                        format!("check exit {:?}: {}", check.code, check.stderr.lines().next().unwrap_or(""))
                    );
                    continue;
                }
                if check.code == Some(2) {
                    *counts.entry("refused by check").or_default() += 1;
                    if !check.stderr.contains("error:") || check.stderr.len() > 2000 {
                        report!("message", format!("refusal without a one-line error: {}", check.stderr));
                    }
                    continue;
                }
                *counts.entry("accepted by check").or_default() += 1;
                let dir = out.join("run");
                let _ = std::fs::remove_dir_all(&dir);
                let mut a = vec![
                    "run".to_string(),
                    scene.clone(),
                    "--out".into(),
                    dir.display().to_string(),
                    "--set".into(),
                    set,
                ];
                for (k, v) in CAPS {
                    if k != key {
                        a.extend(["--set".to_string(), format!("{k}={v}")]);
                    }
                }
                let r = run(&bin, &a, timeout);
                *counts.entry("runs").or_default() += 1;
                if r.timed_out && CAPS.iter().any(|c| c.0 == key) {
                    *counts.entry("long run (a step cap mutated)").or_default() += 1;
                } else if r.timed_out {
                    report!("hang", format!("run past {} s", timeout.as_secs_f64()));
                } else if r.stderr.contains("panicked") || !matches!(r.code, Some(0) | Some(2) | Some(3)) {
                    let first = r.stderr.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
                    report!("crash", format!("run exit {:?}: {first}", r.code));
                } else if r.code == Some(2) {
                    report!("disagreement", format!("check accepts, run refuses: {}", r.stderr.trim()));
                } else {
                    *counts.entry(if r.code == Some(0) { "run ok" } else { "run unstable (exit 3)" }).or_default() += 1;
                    if let Some(w) = non_finite(&dir) {
                        report!("non-finite output", w);
                    }
                }
            }
        }
    }
    let _ = std::fs::write(out.join("findings.txt"), findings.join("\n") + "\n");
    println!("--- counts");
    for (k, v) in &counts {
        println!("{k}: {v}");
    }
}
