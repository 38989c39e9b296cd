//! Helpers shared by the command-line test files (`tests/cli*.rs`): running the program,
//! temporary folders and scenes, reading its outputs. Each test file uses a part of them.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn saltus(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_saltus"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run saltus")
}

/// `saltus closure eval --family <family> --model <model> --input <input>` (the output on
/// stdout).
pub fn closure_eval(family: &str, model: &str, input: &Path) -> Output {
    saltus(&["closure", "eval", "--family", family, "--model", model, "--input", input.to_str().unwrap()])
}

/// `saltus closure check --family <family> --model <model>`.
pub fn closure_check(family: &str, model: &str) -> Output {
    saltus(&["closure", "check", "--family", family, "--model", model])
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A failure that is clean: exit code 2, a line starting with `error:` on stderr (after
/// any warnings, e.g. reference data missing from a checkout without ../shared), no panic.
pub fn assert_clean_failure(o: &Output) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "expected exit 2, got {:?}: {err}", o.status);
    assert!(err.lines().any(|l| l.starts_with("error:")), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// A run that stopped unstable: exit code 3, no panic, and `summary.json` in `out` saying
/// so. Returns stderr and the summary.
pub fn assert_unstable(o: &Output, out: &Path) -> (String, serde_json::Value) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(3), "expected exit 3, got {:?}: {err}", o.status);
    assert!(!err.contains("panicked"), "{err}");
    let s = summary(out);
    assert_eq!(s["ending"].as_str(), Some("unstable"), "{s}");
    (err, s)
}

pub fn tmp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

pub const BASE: &str = "[particles]\ndiameter = 6e-3\ndensity = 2500.0\n";
/// What a scene without `[solver]` (the Eulerian by default) needs beyond [`BASE`] to pass
/// `check`, which refuses what `run` would.
pub const RUNNABLE: &str = "[domain]\nwater_depth = 0.1\ncells = 10\n[closures.granular]\ntype = \"mu_i\"\n";

pub fn check_scene(name: &str, extra: &str) -> Output {
    let d = tmp_dir(name);
    let p = write(&d, "scene.toml", &format!("{BASE}{extra}"));
    saltus(&["check", p.to_str().unwrap()])
}

pub const CASE01: &str = "cases/chassagne2023/case01.toml";
pub const COMPARE01: &str = "cases/chassagne2023/compare_case01_models.toml";

pub fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{} is not a PNG", path.display());
}

pub fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// Rows of a CSV as (header, records).
pub fn read_table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let header = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r.records().map(|x| x.unwrap().iter().map(str::to_string).collect()).collect();
    (header, rows)
}

pub fn cell<'a>(header: &[String], row: &'a [String], name: &str) -> &'a str {
    &row[header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"))]
}
