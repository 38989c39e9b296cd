//! `saltus diagnose` on the command line: a run's folder in, the comparisons out (summary,
//! CSV and PNG per closure and quantity); bad input is a clean error (exit 2) naming the
//! file, the key or the column.

mod common;

use std::path::{Path, PathBuf};

use common::*;

/// Case 1 at 60 cells (0.1 s) into `name`.
fn case01_run(name: &str) -> PathBuf {
    let dir = tmp_dir(name);
    let out = dir.join("run");
    let o = saltus(&[
        "run",
        "cases/chassagne2023/case01.toml",
        "--set",
        "domain.cells=60",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn summary_rows(file: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(file).expect("summary.csv");
    text.lines().skip(1).map(|l| l.split(',').map(str::to_string).collect()).collect()
}

/// Through profiles.csv (11 significant digits) the run's own closure is found again to
/// 1e-9 relative in every comparison of its own (the library test holds it to 1e-10 at
/// full precision); the other g0 models and eq 2.25 do not agree.
#[test]
fn diagnose_a_run_writes_tables_and_figures() {
    let run = case01_run("diagnose_cli");
    let o = saltus(&["diagnose", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("60 cells") && text.contains("g0 closure") && text.contains("a of eq 3.2"), "{text}");
    let out = run.join("diagnose");
    let rows = summary_rows(&out.join("summary.csv"));
    let own = ["g0 closure", "Gamma", "viscosity F2", "heat flux", "J_int eq 3.13"];
    for q in own {
        let r = rows.iter().find(|r| r[2] == q).unwrap_or_else(|| panic!("{q} missing: {rows:?}"));
        let cells: usize = r[3].parse().unwrap();
        let rel: f64 = r[5].parse().unwrap();
        assert!(cells > 5 && rel <= 1e-9, "{q}: {cells} cells, relative RMS {rel}");
    }
    let other = rows.iter().find(|r| r[2] == "g0 carnahan_starling").expect("cs");
    assert!(other[5].parse::<f64>().unwrap() > 0.1);
    for stem in ["frictional-collisional-gamma", "frictional-collisional-g0-closure"] {
        for ext in ["csv", "png"] {
            let f = out.join(format!("{stem}.{ext}"));
            assert!(f.is_file() && std::fs::metadata(&f).unwrap().len() > 100, "{}", f.display());
        }
    }
    let csv = std::fs::read_to_string(out.join("frictional-collisional-gamma.csv")).unwrap();
    assert!(csv.starts_with("z,phi,measured,predicted\n"), "{csv}");
}

#[test]
fn diagnose_bad_input_is_a_clean_error_naming_the_file() {
    let dir = tmp_dir("diagnose_bad");
    // no such folder
    let missing = dir.join("nope");
    let err = assert_clean_failure(&saltus(&["diagnose", missing.to_str().unwrap()]));
    assert!(err.contains("nope") && err.contains("no such run output folder"), "{err}");
    // a folder without profiles.csv
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", empty.to_str().unwrap()]));
    assert!(err.contains("profiles.csv") && err.contains("missing"), "{err}");

    let run = case01_run("diagnose_bad_run");
    let profiles = run.join("profiles.csv");
    let text = std::fs::read_to_string(&profiles).unwrap();
    // a column missing: named, with the hint about the DEM's granular fields
    let without: String = text
        .lines()
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
            let k = header.iter().position(|h| *h == "dissipation").unwrap();
            cells.iter().enumerate().filter(|(i, _)| *i != k).map(|(_, c)| *c).collect::<Vec<_>>().join(",") + "\n"
        })
        .collect();
    std::fs::write(&profiles, &without).unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", run.to_str().unwrap()]));
    assert!(err.contains("profiles.csv") && err.contains("`dissipation`") && err.contains("DEM"), "{err}");
    // a cell that is not a number: file, row and column
    std::fs::write(&profiles, text.replacen("\n", "\nfoo", 2).replacen("\nfoo", "\n", 1)).unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", run.to_str().unwrap()]));
    assert!(err.contains("profiles.csv") && err.contains("row"), "{err}");
    std::fs::write(&profiles, &text).unwrap();

    // closures: TOML syntax, unknown model, out-of-range parameter, a file with a bad key
    let r = run.to_str().unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", "type = "]));
    assert!(err.contains("--closures") && err.contains("TOML"), "{err}");
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", "type = \"mu_x\""]));
    assert!(err.contains("mu_x") && err.contains("mu_i"), "{err}");
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", "{type = \"mu_i\", i0 = -1}"]));
    assert!(err.contains("i0"), "{err}");
    let file = dir.join("closures.toml");
    std::fs::write(&file, "[good]\ntype = \"mu_i\"\n[bad]\ntype = \"mu_k\"\nbogus = 1\n").unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", file.to_str().unwrap()]));
    assert!(err.contains("closures.toml") && err.contains("bogus"), "{err}");
    std::fs::write(&file, "answer = 42\n").unwrap();
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", file.to_str().unwrap()]));
    assert!(err.contains("closures.toml") && err.contains("answer"), "{err}");
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--closures", "no/such/closures.toml"]));
    assert!(err.contains("no/such/closures.toml") && err.contains("no such closures file"), "{err}");
    let err = assert_clean_failure(&saltus(&["diagnose", r, "--phi-min", "2"]));
    assert!(err.contains("--phi-min"), "{err}");
}

/// Named closures from a file: each is evaluated, with its table's name as its label.
#[test]
fn closures_from_a_file_are_labelled_by_their_tables() {
    let run = case01_run("diagnose_named");
    let file = run.join("closures.toml");
    std::fs::write(
        &file,
        "[initial]\ntype = \"frictional_collisional\"\ng0 = { type = \"chialvo_sundaresan\" }\n\
         restitution_model = { type = \"plain\" }\n[proposed]\ntype = \"frictional_collisional\"\n",
    )
    .unwrap();
    let out = run.join("named");
    let o = saltus(&[
        "diagnose",
        run.to_str().unwrap(),
        "--closures",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = summary_rows(&out.join("summary.csv"));
    let rel = |label: &str, q: &str| -> f64 {
        let r = rows.iter().find(|r| r[0] == label && r[2] == q).expect("row");
        r[5].parse().unwrap()
    };
    // the run is the proposed model: the initial one's g0 (a = 0.58) is far from it
    assert!(rel("proposed", "g0 closure") < 1e-9 && rel("initial", "g0 closure") > 0.1, "{rows:?}");
    // plain restitution (e_eff = e = 0.7) dissipates less than Jenkins-Zhang's e_eff
    let bias: f64 = rows.iter().find(|r| r[0] == "initial" && r[2] == "Gamma").unwrap()[6].parse().unwrap();
    assert!(bias < 0.0, "{rows:?}");
}
