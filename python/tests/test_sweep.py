"""saltus.sweep through executors (a thread pool, a process pool, a dask LocalCluster)
against the command line's table, and the xarray views of a run and a sweep with their
netCDF round trips."""

import os
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import saltus

from conftest import ROOT

SWEEP = ROOT / "cases" / "chassagne2023" / "theta_sweep.toml"
CASE02 = ROOT / "cases" / "chassagne2023" / "case02.toml"


def required(module: str):
    """The module, or a failure in CI (where .ci/run installs it), a skip elsewhere."""
    try:
        return __import__(module, fromlist=["_"])
    except ImportError:
        if os.environ.get("CI"):
            pytest.fail(f"{module} is not installed; .ci/run installs it")
        pytest.skip(f"{module} is not installed")


def small_sweep(tmp_path, values="[0.2, 0.4]"):
    f = tmp_path / "s.toml"
    f.write_text(
        f"base = {str(CASE02)!r}\n"
        "set = ['physics.shields=0.2', 'physics.drive=\"water_depth\"', "
        "'physics.shields_weight=\"vertical\"', 'domain.cell_size=\"d/4\"']\n"
        'unset = ["domain.water_depth", "domain.cells"]\n'
        f'[[axis]]\nkey = "physics.shields"\nname = "theta"\nvalues = {values}\n'
    )
    return f


def test_the_thread_pool_sweep_gives_the_command_lines_table(tmp_path, cli):
    r = saltus.sweep(SWEEP, out=tmp_path / "py")
    code, _, err = cli("sweep", str(SWEEP), "--out", str(tmp_path / "cli"), "--quiet")
    assert code == 0, err
    import csv

    with open(tmp_path / "cli" / "sweep.csv") as f:
        rows = list(csv.DictReader(f))
    assert [row["qs_star"] for row in rows] == [row[r.header.index("qs_star")] for row in r.rows]
    assert list(r.column("theta")) == [0.2, 0.4, 0.6, 0.8, 1.0]
    assert all(row[r.header.index("status")] == "done" for row in r.rows)
    assert len(r.fits) == 1 and r.fits[0]["n"] == 5 and r.fits[0]["series"] == ""


def test_a_process_pool_runs_the_points(tmp_path):
    f = small_sweep(tmp_path)
    threads = saltus.sweep(f, out=tmp_path / "threads")
    with ProcessPoolExecutor(max_workers=2) as ex:
        procs = saltus.sweep(f, out=tmp_path / "procs", executor=ex)
    assert not procs.errors
    np.testing.assert_array_equal(procs.column("qs_star"), threads.column("qs_star"))


def test_a_dask_local_cluster_runs_the_points(tmp_path):
    required("dask")
    distributed = required("distributed")
    f = small_sweep(tmp_path)
    here = saltus.sweep(f, out=tmp_path / "here")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            r = saltus.sweep(f, out=tmp_path / "dask", executor=client.get_executor())
    assert not r.errors
    np.testing.assert_array_equal(r.column("qs_star"), here.column("qs_star"))
    assert all(row[r.header.index("status")] == "done" for row in r.rows)


def test_resume_keeps_finished_points(tmp_path):
    f = small_sweep(tmp_path)
    out = tmp_path / "out"
    saltus.sweep(f, out=out)
    kept = (out / "point_0000" / "summary.json").read_text()
    (out / "point_0001" / "summary.json").unlink()
    r = saltus.sweep(f, out=out, resume=True)
    assert (out / "point_0000" / "summary.json").read_text() == kept
    assert (out / "point_0001" / "summary.json").is_file()
    assert all(row[r.header.index("status")] == "done" for row in r.rows)
    (tmp_path / "o").mkdir()
    other = small_sweep(tmp_path / "o", values="[0.3]")
    with pytest.raises(saltus.SceneError, match="another sweep"):
        saltus.sweep(other, out=out, resume=True)


def test_a_run_round_trips_through_netcdf(tmp_path):
    xr = required("xarray")
    r = saltus.run(CASE02, out=tmp_path / "run", set={"output.snapshot_interval": 50.0})
    ds = r.to_xarray()
    np.testing.assert_array_equal(ds["z"].values, r.profiles["z"])
    np.testing.assert_array_equal(ds["phi"].values, r.profiles["phi"])
    assert ds["u_f"].attrs["units"] == "m s-1" and ds["z"].attrs["units"] == "m"
    np.testing.assert_array_equal(ds["qs_star_t"].values, r.timeseries["qs_star"])
    assert ds["phi_snapshot"].dims == ("t_snapshot", "z") and ds.sizes["t_snapshot"] == len(r.snapshots) > 0
    assert ds.attrs["summary_qs_star"] == r.summary["qs_star"]
    assert ds.attrs["scene_toml"] == r.scene_toml
    path = tmp_path / "run.nc"
    r.to_netcdf(path)
    back = xr.open_dataset(path)
    try:
        xr.testing.assert_identical(back.load(), ds)
    finally:
        back.close()


def test_a_sweep_round_trips_through_netcdf_with_its_axes_as_dimensions(tmp_path):
    xr = required("xarray")
    f = tmp_path / "s.toml"
    f.write_text(small_sweep(tmp_path).read_text() + '[[axis]]\nkey = "seed"\nvalues = [1, 2]\n')
    r = saltus.sweep(f, out=tmp_path / "out")
    ds = r.to_xarray()
    assert ds["qs_star"].dims == ("theta", "seed")
    assert list(ds["theta"].values) == [0.2, 0.4] and list(ds["seed"].values) == [1, 2]
    np.testing.assert_array_equal(ds["qs_star"].values.ravel(), r.column("qs_star"))
    assert ds["qs_star"].attrs["units"] == "1"
    path = tmp_path / "sweep.nc"
    r.to_netcdf(path)
    back = xr.open_dataset(path)
    try:
        xr.testing.assert_identical(back.load(), ds)
    finally:
        back.close()
