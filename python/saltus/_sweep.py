"""Sweeps through any executor, and the xarray view of a sweep.

:func:`sweep` writes one resolved scene per point (as ``saltus sweep --emit``), runs the
points through a :class:`concurrent.futures.Executor` (a thread pool by default; a
process pool, ``dask.distributed``'s ``Client.get_executor()`` or
``mpi4py.futures.MPIPoolExecutor`` for a cluster), then gathers them into the table the
command line writes (as ``saltus sweep --collect``). Nothing here computes physics.
"""

from __future__ import annotations

import math
import os
from concurrent.futures import Executor, ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

import numpy as np

from . import _native
from ._outputs import import_xarray, variable
from ._run import fspath, run


def _run_point(scene: str, out: str) -> Dict[str, Any]:
    """Run one point's resolved scene into its folder: what an executor's worker runs.
    Module-level, so that a process pool or a dask worker can pickle it."""
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
        xr = import_xarray()
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
            data = {h: variable(xr, ("point",), self.column(h), h) for h in numeric}
            for h in text:
                data[h] = xr.Variable(("point",), np.array([r[self.header.index(h)] for r in self.rows]))
            return xr.Dataset(data, coords=coords, attrs=attrs)
        shape = tuple(len(a["values"]) for a in self.axes)
        coords = {a["name"]: coord(a) for a in self.axes}
        data = {h: variable(xr, tuple(names), self.column(h).reshape(shape), h) for h in numeric}
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
    path = fspath(file, "file")
    folder, points = _native.sweep_prepare(path, set, None if out is None else fspath(out, "out"), resume)
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
