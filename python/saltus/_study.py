"""Sweeps through any executor, and xarray views of runs and sweeps.

:func:`sweep` writes one resolved scene per point (as ``saltus sweep --emit``), runs the
points through a :class:`concurrent.futures.Executor` (a thread pool by default; a
process pool, ``dask.distributed``'s ``Client.get_executor()`` or
``mpi4py.futures.MPIPoolExecutor`` for a cluster), then gathers them into the table the
command line writes (as ``saltus sweep --collect``). Nothing here computes physics.
"""

from __future__ import annotations

import csv
import json
import math
import os
from concurrent.futures import Executor, ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _native

#: Units of the columns of profiles.csv, timeseries.csv and the summary (SI; "1" for a
#: dimensionless number). A column not listed has no ``units`` attribute.
UNITS: Dict[str, str] = {
    "z": "m",
    "t": "s",
    "phi": "1",
    "u_f": "m s-1",
    "u_p": "m s-1",
    "w_p": "m s-1",
    "theta_g": "m2 s-2",
    "p_p": "Pa",
    "p_p_kinetic": "Pa",
    "p_p_contact": "Pa",
    "tau_p": "Pa",
    "tau_p_kinetic": "Pa",
    "tau_p_contact": "Pa",
    "tau_f": "Pa",
    "sigma_xx": "Pa",
    "sigma_yy": "Pa",
    "sigma_zz": "Pa",
    "nu_t": "m2 s-1",
    "q_s": "m s-1",
    "gamma_dot": "s-1",
    "inertial_number": "1",
    "viscous_number": "1",
    "mu_eff": "1",
    "beta": "kg m-3 s-1",
    "heat_flux": "W m-2",
    "dissipation": "W m-3",
    "drag_dissipation": "W m-3",
    "qs": "m2 s-1",
    "qs_stderr": "m2 s-1",
    "qs_star": "1",
    "qs_star_stderr": "1",
    "shields": "1",
    "shields_nominal": "1",
    "shields_turbulent": "1",
    "bed_surface": "m",
    "bed_height": "m",
    "transport_layer_thickness": "m",
    "flux_layer_thickness": "m",
    "net_transport": "m2",
    "net_transport_stderr": "m2",
    "sim_time_s": "s",
    "wall_time_s": "s",
    "cpu_time_s": "s",
}


def read_columns(path: Path) -> Dict[str, np.ndarray]:
    """A CSV of numbers as column -> float64 array; an empty cell is NaN."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    out: Dict[str, np.ndarray] = {}
    for k, name in enumerate(header):
        out[name] = np.array([float(r[k]) if k < len(r) and r[k] != "" else math.nan for r in body])
    return out


def read_outputs(out: Path) -> Tuple[Dict[str, np.ndarray], List[Tuple[float, Dict[str, np.ndarray]]]]:
    """The time series and the profile snapshots a run wrote into ``out``."""
    ts = out / "timeseries.csv"
    series = read_columns(ts) if ts.is_file() else {}
    snaps: List[Tuple[float, Dict[str, np.ndarray]]] = []
    index = out / "snapshots" / "index.csv"
    if index.is_file():
        with open(index, newline="") as f:
            for row in csv.DictReader(f):
                snaps.append((float(row["t"]), read_columns(out / "snapshots" / row["file"])))
    return series, snaps


def _xarray():
    try:
        import xarray as xr
    except ImportError as e:
        raise ImportError(
            "to_xarray() needs xarray, which is not installed: pip install xarray "
            "(and h5netcdf or netCDF4 for to_netcdf)"
        ) from e
    return xr


def _attrs_of(summary: Dict[str, Any], prefix: str) -> Dict[str, Any]:
    """Summary fields netCDF can hold as attributes (numbers, strings; booleans as 0/1)."""
    a: Dict[str, Any] = {}
    for k, v in summary.items():
        if isinstance(v, bool):
            a[prefix + k] = int(v)
        elif isinstance(v, (int, float, str)):
            a[prefix + k] = v
    return a


def _var(xr, dims, values, name):
    attrs = {"units": UNITS[name]} if name in UNITS else {}
    return xr.Variable(dims, values, attrs=attrs)


def result_dataset(result) -> Any:
    """:meth:`saltus.Result.to_xarray`."""
    xr = _xarray()
    prof = result.profiles
    z = prof.get("z")
    data: Dict[str, Any] = {}
    coords: Dict[str, Any] = {}
    if z is not None:
        coords["z"] = _var(xr, ("z",), z, "z")
        for k, v in prof.items():
            if k != "z":
                data[k] = _var(xr, ("z",), v, k)
    ts = result.timeseries
    if ts and "t" in ts:
        coords["t"] = _var(xr, ("t",), ts["t"], "t")
        for k, v in ts.items():
            if k != "t":
                data[f"{k}_t"] = _var(xr, ("t",), v, k)
    snaps = result.snapshots
    if snaps and z is not None and all(len(s.get("z", [])) == len(z) for _, s in snaps):
        coords["t_snapshot"] = _var(xr, ("t_snapshot",), np.array([t for t, _ in snaps]), "t")
        for k in prof:
            if k != "z" and all(k in s for _, s in snaps):
                data[f"{k}_snapshot"] = _var(xr, ("t_snapshot", "z"), np.stack([s[k] for _, s in snaps]), k)
    attrs = {"ending": result.ending, "scene_toml": result.scene_toml, "summary_json": json.dumps(result.summary)}
    attrs.update(_attrs_of(result.summary, "summary_"))
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _run_point(scene: str, out: str) -> Dict[str, Any]:
    """Run one point's resolved scene into its folder: what an executor's worker runs.
    Module-level, so that a process pool or a dask worker can pickle it."""
    from . import run

    r = run(scene, out=out)
    return {"ending": r.ending, "summary": r.summary}


@dataclass(frozen=True, repr=False)
class SweepResult:
    """A sweep's table, as ``sweep.csv``, with its axes.

    Attributes:
        name: the sweep's name.
        axes: per axis ``{"key", "name", "values", "labels"}``.
        combine: ``"product"`` or ``"zip"``.
        header: the columns of ``sweep.csv``.
        rows: its rows (strings, as in the file).
        out: the sweep's folder.
        files: ``sweep.csv``, ``sweep_seeds.csv`` (with a seed axis), the figure.
        fits: the 3/2-law fit of each series of the figure (one per value of the axes
            other than the swept Shields number and the seed): ``{"series", "a",
            "a_stderr", "theta_c", "theta_c_stderr", "n", "rms", "at_bound", "n_stand_in"}``
            (``n_stand_in``: points without an error of their own, weighed with the
            largest relative error of the series' others).
        warnings: what did not fail the sweep.
        errors: per point that raised in the executor, its message.
    """

    name: str
    axes: List[Dict[str, Any]]
    combine: str
    header: List[str]
    rows: List[List[str]]
    out: Path
    files: List[Path]
    fits: List[Dict[str, Any]] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)
    errors: Dict[int, str] = field(default_factory=dict)

    def column(self, name: str) -> np.ndarray:
        """A numeric column (NaN where empty or not a number)."""
        k = self.header.index(name)

        def num(c: str) -> float:
            try:
                return float(c)
            except ValueError:
                return math.nan

        return np.array([num(r[k]) for r in self.rows])

    def to_dataframe(self) -> Any:
        """The table as a pandas DataFrame (numbers as floats where a column holds them)."""
        import pandas as pd

        df = pd.DataFrame(self.rows, columns=self.header)
        for c in df.columns:
            conv = pd.to_numeric(df[c], errors="coerce")
            if conv.notna().sum() == (df[c] != "").sum():
                df[c] = conv
        return df

    def to_xarray(self) -> Any:
        """The table as an xarray Dataset: for a product of axes, one dimension per axis
        (its values as the coordinate) and every numeric summary field a variable over
        them; for a zip, one dimension ``point`` with the axes as coordinates on it.
        Units in the variables' attributes, the sweep's name and fits as attributes."""
        xr = _xarray()
        names = [a["name"] for a in self.axes]
        skip = set(names) | {"point", "dir"}
        numeric = [h for h in self.header if h not in skip and not np.all(np.isnan(self.column(h)))]
        text = [h for h in self.header if h not in skip and h not in numeric and h in ("status", "ending")]

        def coord(a):
            vals = a["values"]
            return vals if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in vals) else a["labels"]

        attrs: Dict[str, Any] = {"name": self.name, "combine": self.combine}
        for n, f in enumerate(self.fits):
            attrs.update({f"fit{n}_{k}": (int(v) if isinstance(v, bool) else v) for k, v in f.items()})
        if self.combine == "zip" or len(self.rows) != int(np.prod([len(a["values"]) for a in self.axes])):
            coords = {a["name"]: ("point", [coord(a)[a["labels"].index(r[self.header.index(a["name"])])] for r in self.rows]) for a in self.axes}
            data = {h: _var(xr, ("point",), self.column(h), h) for h in numeric}
            for h in text:
                data[h] = xr.Variable(("point",), np.array([r[self.header.index(h)] for r in self.rows]))
            return xr.Dataset(data, coords=coords, attrs=attrs)
        shape = tuple(len(a["values"]) for a in self.axes)
        coords = {a["name"]: coord(a) for a in self.axes}
        data = {h: _var(xr, tuple(names), self.column(h).reshape(shape), h) for h in numeric}
        for h in text:
            data[h] = xr.Variable(tuple(names), np.array([r[self.header.index(h)] for r in self.rows]).reshape(shape))
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def to_netcdf(self, path, **kwargs) -> None:
        """:meth:`to_xarray` written to a netCDF file (``xarray.Dataset.to_netcdf``)."""
        self.to_xarray().to_netcdf(path, **kwargs)

    def __repr__(self) -> str:
        return f"<saltus.SweepResult {self.name!r} {len(self.rows)} points, out={self.out}>"


def sweep(
    file,
    set=None,
    out=None,
    executor: Optional[Executor] = None,
    resume: bool = False,
) -> SweepResult:
    """Run a sweep file through ``executor`` and return its table.

    Args:
        file: the sweep file (the format of ``saltus sweep``, docs/studies.md).
        set: overrides of every point, as :func:`saltus.run`'s ``set``.
        out: the sweep's folder (default ``out/<meta.name>``); each point runs into
            ``out/point_NNNN`` from ``out/point_NNNN.toml``.
        executor: any :class:`concurrent.futures.Executor`; None runs the points on a
            thread pool of one thread per core (the runs release the GIL). For DEM
            points use a process pool, a ``dask.distributed`` client's
            ``get_executor()`` or an ``mpi4py.futures.MPIPoolExecutor``: the workers
            need the ``saltus`` package and the folder ``out`` (a shared file system).
        resume: keep the points whose summaries in ``out`` say they finished (the
            folder must hold this sweep).

    Returns:
        the :class:`SweepResult` of every point (also written to ``out/sweep.csv``).
        A point whose run raised in the executor has the status of what it left behind
        and its message in ``SweepResult.errors``.

    Raises:
        SceneError: the sweep or a point's scene does not load, or ``out`` holds
            another sweep.
    """
    from . import _path

    path = _path(file, "file")
    folder, points = _native.sweep_prepare(path, set, None if out is None else _path(out, "out"), resume)
    out_dir = Path(folder)
    todo = [p for p in points if not p["finished"]]
    own = executor is None
    pool = ThreadPoolExecutor(max_workers=os.cpu_count() or 1) if own else executor
    errors: Dict[int, str] = {}
    try:
        futures = [(p["index"], pool.submit(_run_point, p["scene"], p["dir"])) for p in todo]
        for i, fut in futures:
            try:
                fut.result()
            except KeyboardInterrupt:
                raise
            except Exception as e:  # a point's failure is its row's status, not the sweep's end
                errors[i] = f"{type(e).__name__}: {e}"
    finally:
        if own:
            pool.shutdown(wait=True)
    t = _native.sweep_collect(path, set, folder)
    return SweepResult(
        name=t["name"],
        axes=t["axes"],
        combine=t["combine"],
        header=t["header"],
        rows=t["rows"],
        out=out_dir,
        files=[Path(f) for f in t["files"]],
        fits=list(t["fits"]),
        warnings=list(t["warnings"]),
        errors=errors,
    )


#: Columns of the comparison tables that hold text (a variant named "30" stays "30").
_TEXT_COLUMNS = ("variant", "solver", "steady", "error", "purpose", "ending")


def _read_table(path: Optional[str]) -> Optional[Dict[str, List[Any]]]:
    # a CSV of saltus as columns: numbers where every cell reads as one (empty: NaN)
    if path is None:
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    columns: Dict[str, List[Any]] = {}
    for k, name in enumerate(header):
        cells = [r[k] for r in body]
        if name in _TEXT_COLUMNS:
            columns[name] = cells
            continue
        try:
            columns[name] = [float(c) if c != "" else math.nan for c in cells]
        except ValueError:
            columns[name] = cells
    return columns


@dataclass
class CompareResult:
    """What :func:`compare` wrote: the comparison table and, with a ``[reference]`` in the
    compare file, the work-precision table (each a dict of columns, as the CSV files in
    ``out``; ``pandas.DataFrame(result.precision)`` makes a frame of one)."""

    out: Path
    table: Dict[str, List[Any]]
    precision: Optional[Dict[str, List[Any]]]
    figure: Optional[Path]
    precision_figure: Optional[Path]
    failures: int
    warnings: List[str] = field(default_factory=list)


def compare(file, set=None, out=None) -> CompareResult:
    """Run a compare file (the format of ``saltus compare``, docs/studies.md) in this
    process and return its tables.

    Args:
        file: the compare file.
        set: overrides of every variant, as :func:`saltus.run`'s ``set``.
        out: the output folder (default ``out/<meta.name>``).

    Raises:
        SceneError: the compare file or its base scene does not load.
        RunError: the tables could not be written.
    """
    from . import _path

    raw = _native.compare(_path(file, "file"), set, None if out is None else _path(out, "out"))
    opt = lambda p: None if p is None else Path(p)  # noqa: E731
    return CompareResult(
        out=Path(raw["out"]),
        table=_read_table(raw["table"]) or {},
        precision=_read_table(raw["precision"]),
        figure=opt(raw["figure"]),
        precision_figure=opt(raw["precision_figure"]),
        failures=raw["failures"],
        warnings=list(raw["warnings"]),
    )


@dataclass
class CalibrationResult:
    """What :func:`calibrate` wrote (docs/calibration.md): each fitted constant with its
    errors, the correlation matrix, the misfit at the start and at the optimum against
    the reference's scatter, every model run, and the paths of the outputs."""

    out: Path
    #: one dict per constant: ``key``, ``start``, ``value``, ``stderr`` (scaled by the
    #: misfit the model cannot remove), ``stderr_statistical`` (the scatter alone),
    #: ``stderr_profile`` ([below, above], from the profile likelihood), ``bounds``,
    #: ``at_bound``, ``profile_likelihood`` (points of ``value``, ``delta_chi2``, ``params``)
    parameters: List[Dict[str, Any]]
    #: correlation matrix of the constants, in the order of ``parameters``
    correlation: np.ndarray
    #: covariance matrix, scaled as ``stderr``
    covariance: np.ndarray
    chi2_start: float
    chi2: float
    dof: float
    #: per term at the start and at the optimum: ``term``, ``difference``, ``scatter``, ``ratio``
    misfit: Dict[str, List[Dict[str, Any]]]
    #: every model run, as the columns of calibration.csv
    evaluations: Dict[str, List[Any]]
    #: the calibrated closures file, for :func:`saltus.run`'s ``closures``
    calibrated: Path
    #: stopping reason, runs, CPU and wall time
    optimiser: Dict[str, Any]
    text: str
    files: List[Path] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)

    @property
    def values(self) -> Dict[str, float]:
        """The optimum as key -> value."""
        return {p["key"]: p["value"] for p in self.parameters}


def calibrate(file, set=None, out=None):
    """Fit closure constants jointly against a reference, as ``saltus calibrate FILE``
    (the calibrate file's format is in docs/calibration.md), in this process.

    Args:
        file: the calibrate file.
        set: overrides of every run of the base scene, as :func:`saltus.run`'s ``set``.
        out: the output folder (default ``out/<meta.name>``).

    Returns:
        a :class:`CalibrationResult`.

    Raises:
        SceneError: the calibrate file, its base scene or its reference is refused (by
            file and key, as the command line refuses it).
        RunError: a model run the analysis needs failed.
    """
    from . import _path

    raw = _native.calibrate(_path(file, "file"), set, None if out is None else _path(out, "out"), False)
    with open(raw["json"]) as f:
        j = json.load(f)
    nan = lambda m: np.array([[math.nan if v is None else v for v in row] for row in m], dtype=float)  # noqa: E731
    out_dir = Path(raw["out"])
    return CalibrationResult(
        out=out_dir,
        parameters=j["parameters"],
        correlation=nan(j["correlation"]),
        covariance=nan(j["covariance"]),
        chi2_start=j["misfit"]["chi2_start"],
        chi2=j["misfit"]["chi2"],
        dof=j["misfit"]["dof"],
        misfit={"start": j["misfit"]["start"], "optimum": j["misfit"]["optimum"]},
        evaluations=_read_table(str(out_dir / "calibration.csv")) or {},
        calibrated=out_dir / "calibrated.toml",
        optimiser=j["optimiser"],
        text=raw["text"],
        files=[Path(p) for p in raw["files"]],
        warnings=list(raw["warnings"]),
    )


def check_calibration(file, set=None) -> str:
    """Check a calibrate file as :func:`calibrate` would, without running the model (as
    ``saltus calibrate FILE --check``); the line saying what it would fit.

    Raises:
        SceneError: as :func:`calibrate`.
    """
    from . import _path

    return _native.calibrate(_path(file, "file"), set, None, True)["text"]
