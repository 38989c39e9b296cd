"""saltus.run and saltus.check: physics of small scenes, identity with the command line,
errors, interruption."""

import json
import math
import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import saltus
from conftest import cli_error

CASE01 = "cases/chassagne2023/case01.toml"
LAMINAR = "cases/verification/open_channel_laminar.toml"


def test_laminar_open_channel_matches_the_half_poiseuille_parabola(root):
    # scene: G = -dp/dx = 0.8 Pa/m, h = 5 mm, mu = rho nu = 1e-3 Pa s; the second-order
    # finite volumes are exact at the cell centres, so only the steady tolerance (1e-12 /s)
    # is left: 1e-10 of the surface velocity (the scene's own target)
    r = saltus.run(root / LAMINAR, out=False)
    assert r.ending == "steady"
    g, mu, h = 0.8, 1.0e3 * 1.0e-6, 0.005
    z, u = r.profiles["z"], r.profiles["u_f"]
    surface = g * h * h / (2 * mu)
    exact = g / (2 * mu) * (2 * h * z - z * z)
    assert z.dtype == np.float64 and z.shape == (50,)
    assert np.max(np.abs(u - exact)) < 1e-10 * surface
    assert r.out is None and r.figure is None
    assert r.summary["ending"] == "steady" and r.summary["cells"] == 50


def test_case01_from_python_is_the_command_line_run(root, cli, tmp_path):
    py_out, cli_out = tmp_path / "py", tmp_path / "cli"
    r = saltus.run(str(root / CASE01), out=py_out)
    code, _, err = cli("run", CASE01, "--out", str(cli_out))
    assert code == 0, err
    with open(cli_out / "summary.json") as f:
        from_cli = json.load(f)
    with open(py_out / "summary.json") as f:
        from_py_file = json.load(f)
    # identity: the same program, bit for bit; only the wall times differ
    assert r.summary["qs_star"] == from_cli["qs_star"]
    for s in (r.summary, from_py_file, from_cli):
        s.pop("wall_time_s")
        s.pop("cpu_time_s", None)
        assert set(s.pop("timing")["stages"]) >= {"coefficients", "momentum", "output"}
    assert r.summary == from_py_file == from_cli
    assert (py_out / "profiles.csv").read_text() == (cli_out / "profiles.csv").read_text()
    # physics: Chassagne et al. 2023 case 1, coupled fluid-DEM qs* = 2.34; the continuum
    # model is within 10 % of it (docs/validation.md: +8 %)
    assert r.ending == "steady"
    assert abs(r.summary["qs_star"] / 2.34 - 1) < 0.10
    # the in-memory profiles are the CSV's at full precision (the CSV keeps 11 digits)
    csv = np.genfromtxt(py_out / "profiles.csv", delimiter=",", names=True)
    assert list(csv.dtype.names) == list(r.profiles)
    for name, values in r.profiles.items():
        np.testing.assert_allclose(values, csv[name], rtol=1e-10, atol=0, err_msg=name)
    assert r.out == py_out and r.figure == py_out / "profiles.png" and r.figure.is_file()
    for f in ("profiles.csv", "summary.json", "scene.toml", "manifest.json"):
        assert (py_out / f).is_file(), f
    assert r.scene_toml == (py_out / "scene.toml").read_text()
    assert "qs* = " in r.text and r.wall > 0


def test_default_out_is_the_command_lines(root, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = saltus.run(root / LAMINAR)
    assert r.out == Path("out/verification_open_channel_laminar")
    assert (tmp_path / "out" / "verification_open_channel_laminar" / "summary.json").is_file()


def test_dataframe_has_one_row_per_cell(root):
    pd = pytest.importorskip("pandas")
    r = saltus.run(root / LAMINAR, out=False)
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(r.profiles) and len(df) == 50
    assert r.profiles_df.equals(df)


def test_dataframe_without_pandas_says_how_to_get_it(root, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_pandas(name, *args, **kwargs):
        if name == "pandas":
            raise ImportError("No module named 'pandas'")
        return real_import(name, *args, **kwargs)

    r = saltus.run(root / LAMINAR, out=False)
    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match="pip install pandas"):
        r.to_dataframe()


def test_set_has_the_command_lines_semantics(root, cli, monkeypatch):
    monkeypatch.chdir(root)  # where the command line runs: the same paths in the text
    scene = root / CASE01
    overrides = {"closures.drag": {"type": "stokes"}, "physics.slope": 0.02}
    as_dict = saltus.check(scene, set=overrides)
    as_cli = saltus.check(scene, set=['closures.drag={type="stokes"}', "physics.slope=0.02"])
    assert as_dict == as_cli
    # a model switch replaces the whole table; later keys apply after earlier ones
    assert as_dict["closures"]["drag"] == {"type": "stokes"}
    assert as_dict["physics"]["slope"] == 0.02
    # the TOML text is the command line's, after its header comment
    code, out, err = cli("check", CASE01, "--set", 'closures.drag={type="stokes"}', "--set", "physics.slope=0.02")
    assert code == 0, err
    assert out.split("\n", 1)[1] == saltus.check(CASE01, set=overrides, toml=True)
    # values of every TOML kind: bool, int, str, nested dict
    d = saltus.check(
        scene,
        set={"seed": 7, "solver.lagrangian.stop_when_steady": True, "meta.name": "x y", "domain.cells": np.int64(60)},
    )
    assert d["seed"] == 7 and d["solver"]["lagrangian"]["stop_when_steady"] is True
    assert d["meta"]["name"] == "x y" and d["domain"]["cells"] == 60


@pytest.mark.parametrize(
    "key,value,cli_value",
    [
        ("physics.slopee", 0.1, "0.1"),  # unknown key
        ("physics.slope", 2.0, "2.0"),  # out of range
        ("closures.drag", {"type": "stoke"}, '{type="stoke"}'),  # unknown model name
        ("closures.fluctuation", {"type": "eddy_interaction"}, '{type="eddy_interaction"}'),  # unmet need
    ],
)
def test_errors_carry_the_command_lines_message(root, cli, monkeypatch, key, value, cli_value):
    monkeypatch.chdir(root)  # where the command line runs: the same file name in messages
    code, _, err = cli("check", CASE01, "--set", f"{key}={cli_value}")
    assert code == 2
    for call in (saltus.check, saltus.run):
        with pytest.raises(saltus.SceneError) as e:
            call(CASE01, set={key: value})
        assert str(e.value) == cli_error(err)
        assert isinstance(e.value, ValueError)
        assert e.value.file == CASE01
        assert e.value.key is not None and e.value.key.startswith(key.split(".")[0])


def test_syntax_and_missing_file_errors(tmp_path, cli):
    bad = tmp_path / "bad.toml"
    bad.write_text("[particles]\ndiameter = = 1\n")
    code, _, err = cli("check", str(bad))
    with pytest.raises(saltus.SceneError) as e:
        saltus.check(bad)
    assert str(e.value) == cli_error(err) and e.value.key is None and e.value.file == str(bad)
    missing = tmp_path / "missing.toml"
    code, _, err = cli("run", str(missing))
    with pytest.raises(saltus.SceneError) as e:
        saltus.run(missing)
    assert str(e.value) == cli_error(err)


def test_an_output_that_cannot_be_written_is_a_run_error(root, cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    out = blocker / "sub"
    code, _, err = cli("run", LAMINAR, "--out", str(out))
    assert code == 2
    with pytest.raises(saltus.RunError) as e:
        saltus.run(root / LAMINAR, out=out)
    assert str(e.value) == cli_error(err)
    assert e.value.file == str(out)


def test_an_unstable_run_returns_its_last_good_state(root, cli, tmp_path):
    # the command line's recipe (tests/cli_run.rs): steps of 0.1 s allowed to change phi by
    # 1e-6 are all rejected until dt falls under dt_min
    sets = {
        "domain.cells": 60,
        "solver.eulerian.max_phi_change": 1e-6,
        "solver.eulerian.dt_initial": 0.1,
        "solver.eulerian.dt_min": 0.01,
    }
    r = saltus.run(root / CASE01, set=sets, out=tmp_path / "py")
    assert r.ending == "unstable"
    assert r.breakdown["place"]["kind"] == "cell" and "reason" in r.breakdown
    assert r.summary["ending"] == "unstable" and "cell" in r.summary["error"]
    code, _, err = cli("run", CASE01, *sum((["--set", f"{k}={v}"] for k, v in sets.items()), []), "--out", str(tmp_path / "cli"))
    assert code == 3, err
    from_cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    for key in ("wall_time_s", "cpu_time_s", "timing"):
        from_cli.pop(key, None)
    assert {k: v for k, v in r.summary.items() if k not in ("wall_time_s", "cpu_time_s", "timing")} == from_cli


def _long_run_set():
    # case 1 with no steady criterion: runs until stopped, or for a million steps (about
    # 40 s at 25000 steps per second on a loaded 2-core machine), so that an interrupt the
    # run missed fails the test instead of hanging it
    return {
        "solver.eulerian.steady_tolerance": 0.0,
        "solver.eulerian.end_time": 1.0e9,
        "solver.eulerian.max_steps": 1000000,
    }


@pytest.mark.parametrize("how", ["interrupt_main", "sigint"])
def test_ctrl_c_stops_the_run_writes_its_outputs_then_raises(root, tmp_path, how):
    out = tmp_path / how
    delay = 0.5

    def fire():
        time.sleep(delay)
        if how == "sigint":
            os.kill(os.getpid(), signal.SIGINT)
        else:
            import _thread

            _thread.interrupt_main()

    # Ctrl-C as a terminal delivers it: Python's handler on SIGINT. A process started in the
    # background of a shell without job control inherits SIGINT ignored, and then neither
    # the signal nor interrupt_main reaches Python (the run would go on to its end)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Thread(target=fire)
    started = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as e:
            saltus.run(root / CASE01, set=_long_run_set(), out=out)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, previous)
    elapsed = time.perf_counter() - started
    # signals are looked at every 0.2 s of wall time, then the outputs are written
    assert elapsed < delay + 0.2 + 2.0, elapsed
    result = e.value.result
    assert result.ending == "interrupted" and result.summary["ending"] == "interrupted"
    assert result.summary["sim_time_s"] > 0 and math.isfinite(result.summary["sim_time_s"])
    written = json.loads((out / "summary.json").read_text())
    assert written["ending"] == "interrupted" and written["steps"] == result.summary["steps"]


def test_other_threads_run_during_a_run(root):
    # the GIL is released: a thread sleeping 1 ms at a time keeps ticking while the solver
    # works; holding the GIL, the solver would leave a gap of its whole wall time
    stop = threading.Event()
    ticks = []

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    # a run of a few tenths of a second: long against the ticks, whatever the machine
    sets = {"solver.eulerian.steady_tolerance": 0.0, "solver.eulerian.end_time": 1.0e4}
    t = threading.Thread(target=count)
    t.start()
    try:
        r = saltus.run(root / CASE01, set=sets, out=False)
    finally:
        stop.set()
        t.join()
    assert r.ending == "end_time" and r.wall > 0.1
    gap = max(np.diff(ticks))
    assert gap < 0.5 * r.wall, (gap, r.wall)


def test_warm_start_is_the_command_lines(root, cli, tmp_path):
    """`warm_start` starts from a finished run's final state as `--warm-start` does: an
    Eulerian column from its own steady profiles is steady again in a fifth of the steps
    or fewer, with the same rate (the column's fixed point, to the steady tolerance), and
    the Python run writes what the command line writes; refusals name the folder."""
    scene = str(root / "tests/fixtures/scenes/small_dem_bed.toml")
    two_fluid = {"solver.type": "eulerian", "closures.granular": {"type": "mu_i"}}
    first = saltus.run(scene, set=two_fluid, out=tmp_path / "first")
    again = saltus.run(scene, set=two_fluid, out=tmp_path / "again", warm_start=tmp_path / "first")
    assert first.ending == again.ending == "steady"
    assert again.summary["steps"] * 5 < first.summary["steps"]
    assert again.summary["qs_star"] == pytest.approx(first.summary["qs_star"], rel=1e-5)
    code, _, err = cli(
        "run", scene, "--quiet", "--out", str(tmp_path / "cli"),
        "--set", "solver.type=eulerian", "--set", "closures.granular.type=mu_i",
        "--warm-start", str(tmp_path / "first"),
    )
    assert code == 0, err
    assert (tmp_path / "cli" / "profiles.csv").read_text() == (tmp_path / "again" / "profiles.csv").read_text()
    with pytest.raises(saltus.SceneError, match="warm_start.*not a run folder"):
        saltus.run(scene, out=tmp_path / "x", warm_start=tmp_path / "nowhere")
    with pytest.raises(saltus.SceneError, match="restart"):
        saltus.run(scene, out=tmp_path / "y", restart=tmp_path / "first", warm_start=tmp_path / "first")
