"""`saltus.run_seeds`: several seeds of a DEM scene as one answer, as `saltus run --seeds N`
writes it (the pooled rate, each seed's folder bit for bit), from a bank of developed
states, and its refusals."""

import json

import pytest

import saltus

COMMON = {"solver.lagrangian.fluid_period": 2e-3, "seed": 3}


def cli_set(d):
    args = []
    for k, v in d.items():
        args += ["--set", f"{k}={v}"]
    return args


def test_seeds_pool_as_the_command_line_pools_them(root, cli, tmp_path):
    """Two seeds stopped together by the pooled rule: the answer is the mean of the two
    window means, its error the larger of the within- and between-seed errors and at most
    the target, and every file the command line writes for the same seeds is the same."""
    scene = str(root / "tests/fixtures/scenes/small_dem_bed.toml")
    s = dict(COMMON, **{"solver.lagrangian.end_time": 30, "solver.lagrangian.target_error": 0.05})
    r = saltus.run_seeds(scene, 2, set=s, out=tmp_path / "py")
    assert r.ending == "target_error" and r.errors == []
    assert [row["seed"] for row in r.runs] == [3, 4]
    q = [row["qs_window"] for row in r.runs]
    e = [row["qs_window_stderr"] for row in r.runs]
    within = (e[0] ** 2 + e[1] ** 2) ** 0.5 / 2
    between = abs(q[0] - q[1]) / 2
    assert r.qs == pytest.approx((q[0] + q[1]) / 2, rel=1e-12)
    assert r.qs_stderr == pytest.approx(max(within, between), rel=1e-12)
    assert r.qs_stderr <= 0.05 * r.qs
    assert r.qs_star_stderr / r.qs_star == pytest.approx(r.qs_stderr / r.qs, rel=1e-12)
    assert all(row["summary"]["ending"] == "target_error" for row in r.runs)
    assert json.loads(r.file.read_text())["qs"] == r.qs
    code, _, err = cli("run", scene, "--quiet", "--seeds", "2", "--out", str(tmp_path / "cli"), *cli_set(s))
    assert code == 0, err
    for k in (3, 4):
        for f in ("profiles.csv", "timeseries.csv"):
            py = (tmp_path / "py" / f"seed_{k}" / f).read_text()
            assert py == (tmp_path / "cli" / f"seed_{k}" / f).read_text(), (k, f)


def test_seeds_start_from_a_bank_and_bad_input_is_refused(root, tmp_path):
    """A run of two seeds is the bank of a second: each seed starts from its own parent's
    bed (its first Shields number is its parent's last); too few states, a wrong number of
    seeds and an Eulerian scene are refused by name."""
    scene = str(root / "tests/fixtures/scenes/small_dem_bed.toml")
    short = dict(COMMON, **{"solver.lagrangian.end_time": 0.05})
    bank = saltus.run_seeds(scene, 2, set=short, out=tmp_path / "bank")
    answer = saltus.run_seeds(scene, 2, set=short, out=tmp_path / "answer", warm_start=bank.out)
    def shields(folder):
        lines = (folder / "timeseries.csv").read_text().splitlines()
        col = lines[0].split(",").index("shields")
        return [float(line.split(",")[col]) for line in lines[1:]]

    last = [shields(tmp_path / "bank" / f"seed_{k}")[-1] for k in (3, 4)]
    first = [shields(tmp_path / "answer" / f"seed_{k}")[0] for k in (3, 4)]
    assert last[0] > 0 and last[1] > 0 and last[0] != last[1], last
    assert first == pytest.approx(last, rel=1e-12)
    assert answer.runs[0]["summary"] == json.loads((tmp_path / "answer" / "seed_3" / "summary.json").read_text())
    with pytest.raises(saltus.RunError, match="3 developed states"):
        saltus.run_seeds(scene, 3, set=short, out=tmp_path / "three", warm_start=bank.out)
    for n in (0, -1, 2.5, True):
        with pytest.raises(ValueError, match="seeds"):
            saltus.run_seeds(scene, n, set=short, out=tmp_path / "bad")
    with pytest.raises(saltus.RunError, match="256"):
        saltus.run_seeds(scene, 257, set=short, out=tmp_path / "many")
    with pytest.raises(saltus.RunError, match="lagrangian"):
        saltus.run_seeds(scene, 2, set={"solver.type": "eulerian", "closures.granular": {"type": "mu_i"}}, out=tmp_path / "eul")
