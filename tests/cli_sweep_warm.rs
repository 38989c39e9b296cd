//! DEM warm starts in `saltus sweep` (`warm_start = true`): a point starts its flow from
//! the grains its parent left in its final checkpoint, without a deposition of its own; a
//! parent whose grains the point's scene cannot take leaves it to start from rest with the
//! reason recorded; the numbers do not depend on the number of jobs.

mod common;

use std::path::{Path, PathBuf};

use common::*;

/// A sweep over the small deposited DEM bed (86 grains, 0.1 s of deposition, 0.02 s of
/// flow) with `extra` (TOML text: the warm start and the axes).
fn dem_sweep(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes/small_dem_bed.toml");
    write(dir, name, &format!("base = {:?}\n{extra}", base.display().to_string()))
}

const SLOPES: &str = "[[axis]]\nkey = \"physics.slope\"\nvalues = [0.1, 0.12, 0.14]\n";

fn sweep(file: &Path, out: &Path, jobs: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let o = saltus(&["sweep", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--jobs", jobs, "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    read_table(&out.join("sweep.csv"))
}

fn num(header: &[String], row: &[String], name: &str) -> f64 {
    cell(header, row, name).parse().unwrap_or_else(|_| panic!("{name} = {:?}", cell(header, row, name)))
}

/// The transport rate of the first row of a run's time series: the state its flow
/// starts from.
fn first_qs(dir: &Path) -> f64 {
    let (header, rows) = read_table(&dir.join("timeseries.csv"));
    assert_eq!(cell(&header, &rows[0], "t").parse::<f64>().unwrap(), 0.0, "{}", dir.display());
    num(&header, &rows[0], "qs")
}

/// The fluid column a run put over its deposit, from its profiles: the number of cells
/// and the height of the last cell's centre (m).
fn column(dir: &Path) -> (usize, f64) {
    let (header, rows) = read_table(&dir.join("profiles.csv"));
    let top = rows.last().map(|r| num(&header, r, "z")).unwrap_or(f64::NAN);
    (rows.len(), top)
}

/// Each point after the first starts from its parent's grains: the parent leaves its
/// final checkpoint, the child takes no deposition steps (all its steps are flow steps),
/// keeps the parent's grains, and its flow starts on a moving bed, where from rest the bed
/// starts still.
#[test]
fn a_warm_started_dem_point_starts_its_flow_on_its_parents_moving_bed() {
    let d = tmp_dir("sweep_warm_dem");
    let warm = dem_sweep(&d, "warm.toml", &format!("warm_start = true\n{SLOPES}"));
    let cold = dem_sweep(&d, "cold.toml", SLOPES);
    let (hw, rw) = sweep(&warm, &d.join("warm"), "2");
    let (hc, rc) = sweep(&cold, &d.join("cold"), "2");
    for k in 0..3 {
        assert_eq!(cell(&hw, &rw[k], "status"), "done", "point {k}");
        assert_eq!(cell(&hw, &rw[k], "warm_start_refused"), "", "point {k}");
        let from = cell(&hw, &rw[k], "warm_start_from");
        assert_eq!(from, if k == 0 { String::new() } else { format!("point_{:04}", k - 1) }, "point {k}");
        assert_eq!(cell(&hc, &rc[k], "warm_start_from"), "", "point {k} of the sweep without warm starts");
        let (dw, dc) = (d.join("warm").join(format!("point_{k:04}")), d.join("cold").join(format!("point_{k:04}")));
        assert!(dw.join("checkpoint.bin").is_file(), "point {k} leaves no checkpoint for its children");
        // from rest: a deposition, then a flow on a bed at rest
        assert!(num(&hc, &rc[k], "total_steps") > num(&hc, &rc[k], "steps"), "point {k} from rest");
        assert_eq!(first_qs(&dc), 0.0, "point {k} from rest");
        if k == 0 {
            assert!(num(&hw, &rw[k], "total_steps") > num(&hw, &rw[k], "steps"));
            assert_eq!(first_qs(&dw), 0.0);
        } else {
            assert_eq!(num(&hw, &rw[k], "total_steps"), num(&hw, &rw[k], "steps"), "point {k}: a deposition");
            assert!(first_qs(&dw) > 0.0, "point {k}: its flow starts on a bed at rest");
            assert_eq!(cell(&hw, &rw[k], "particles"), cell(&hw, &rw[k - 1], "particles"), "point {k}");
            // the grains still settle when the flow starts (0.1 s of deposition), so the
            // parent's bed at its end is not its deposit: the free surface stands the
            // same water depth above the deposit the chain's first point measured
            assert_eq!(column(&dw), column(&d.join("warm").join("point_0000")), "point {k}: the column");
        }
    }
}

/// The deposit's surface is measured on every grain: under water shallower than the gap
/// between the scene's nominal bed (`bed_height`) and the deposit's top, the grains
/// standing above the scene's column count, and the surface is where it is under deep
/// water.
#[test]
fn the_deposit_surface_is_measured_above_a_shallow_scenes_column() {
    let d = tmp_dir("deposit_surface_shallow");
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/scenes/small_dem_bed.toml");
    let surface = |depth: f64| {
        let out = d.join(format!("h{depth}"));
        let o = saltus(&[
            "run",
            base.to_str().unwrap(),
            "--set",
            "solver.lagrangian.settle_time=0.4",
            "--set",
            &format!("domain.water_depth={depth}"),
            "--out",
            out.to_str().unwrap(),
            "-q",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (n, z) = column(&out);
        // the top of the column, whose n cells are uniform, less the water above the deposit
        z * n as f64 / (n as f64 - 0.5) - depth
    };
    let (shallow, deep) = (surface(0.0005), surface(0.03));
    let (d_grain, bed_height) = (6.0e-3, 0.012);
    // the deposit (packing 0.55-0.6) stands 0.6 d above bed_height (at bed_phi 0.6): a
    // measure capped by the column would lie below bed_height + 0.0005
    assert!(shallow > bed_height + 0.0005 + 0.25 * d_grain, "surface {shallow} m: capped by the scene's column");
    assert!((shallow - deep).abs() < 0.5 * d_grain, "shallow {shallow} m, deep {deep} m");
}

/// Which state a point starts from is fixed by its chain, not by the scheduling: one job
/// and two give the same numbers in every column but the timings.
#[test]
fn dem_warm_starts_give_the_same_numbers_on_one_job_as_on_two() {
    let d = tmp_dir("sweep_warm_dem_jobs");
    let warm = dem_sweep(&d, "warm.toml", &format!("warm_start = true\n{SLOPES}"));
    let (h1, r1) = sweep(&warm, &d.join("one"), "1");
    let (h2, r2) = sweep(&warm, &d.join("two"), "2");
    assert_eq!(h1, h2);
    let timings = ["cpu_time_s", "wall_time_s", "particle_steps_per_s", "timing"];
    let mut compared = 0;
    for (k, (a, b)) in r1.iter().zip(&r2).enumerate() {
        for (c, name) in h1.iter().enumerate() {
            if !timings.contains(&name.as_str()) {
                assert_eq!(a[c], b[c], "point {k}, column {name}");
                compared += 1;
            }
        }
    }
    assert!(h1.iter().any(|c| c == "qs_star") && compared > 3 * 10, "{h1:?}");
}

/// A parent in another lateral cell holds other grains: the point starts from rest (with
/// its own deposition), the reason naming the key in the manifest and the table.
#[test]
fn a_dem_warm_start_across_a_lateral_cell_axis_is_refused_and_starts_from_rest() {
    let d = tmp_dir("sweep_warm_dem_length");
    let file = dem_sweep(
        &d,
        "length.toml",
        "warm_start = true\n[[axis]]\nkey = \"solver.lagrangian.length\"\nvalues = [0.03, 0.036]\n",
    );
    let out = d.join("out");
    let (h, r) = sweep(&file, &out, "2");
    assert_eq!(cell(&h, &r[1], "status"), "done");
    assert_eq!(cell(&h, &r[1], "warm_start_from"), "");
    let why = cell(&h, &r[1], "warm_start_refused");
    assert!(why.contains("solver.lagrangian.length") && why.contains("point_0000"), "{why}");
    assert!(num(&h, &r[1], "total_steps") > num(&h, &r[1], "steps"), "no deposition: not from rest");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(manifest["points"][1]["warm_start_refused"].as_str(), Some(why));
    assert!(manifest["points"][1].get("warm_start_from").is_none(), "{}", manifest["points"][1]);
    assert!(manifest["points"][0].get("warm_start_refused").is_none(), "{}", manifest["points"][0]);
}

/// A parent that ended done within its deposition (at its step cap) has no deposited bed
/// to give: its child starts from rest, told why.
#[test]
fn a_parent_stopped_in_its_deposition_gives_no_warm_start() {
    let d = tmp_dir("sweep_warm_dem_deposition");
    let file = dem_sweep(
        &d,
        "cap.toml",
        "warm_start = true\n[[axis]]\nkey = \"solver.lagrangian.max_steps\"\nvalues = [500, 100000]\n",
    );
    let (h, r) = sweep(&file, &d.join("out"), "1");
    assert_eq!((cell(&h, &r[0], "status"), cell(&h, &r[0], "ending")), ("done", "max_steps"));
    assert_eq!(cell(&h, &r[1], "warm_start_from"), "");
    let why = cell(&h, &r[1], "warm_start_refused");
    assert!(why.contains("deposition"), "{why}");
    assert!(num(&h, &r[1], "total_steps") > num(&h, &r[1], "steps"));
}

/// A DEM point on threads of its own (`solver.lagrangian.threads = 1`: the run's own pool):
/// the manifest's CPU time is the run's, its summary's, not the driving thread's alone.
#[test]
fn a_dem_point_on_its_own_threads_counts_their_cpu_time() {
    let d = tmp_dir("sweep_dem_cpu");
    let file = dem_sweep(
        &d,
        "own.toml",
        "set = [\"solver.lagrangian.threads=1\"]\n[[axis]]\nkey = \"physics.slope\"\nvalues = [0.1]\n",
    );
    let out = d.join("out");
    let (h, r) = sweep(&file, &out, "1");
    assert_eq!(cell(&h, &r[0], "status"), "done");
    let m: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    let run = summary(&out.join("point_0000"))["cpu_time_s"].as_f64().unwrap();
    assert!(run > 0.0);
    assert_eq!(m["points"][0]["cpu_time_s"].as_f64(), Some(run), "{m}");
}
