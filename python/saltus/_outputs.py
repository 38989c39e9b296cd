"""A run's output files read back, and the xarray views of runs and sweeps.

The CSV files the command line writes (``timeseries.csv``, the profile snapshots, the
comparison and calibration tables) as columns of numbers, and the Dataset of a run with the
units of its columns. Nothing here computes physics.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import numpy as np


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


#: Columns of the comparison tables that hold text (a variant named "30" stays "30").
_TEXT_COLUMNS = ("variant", "solver", "steady", "error", "purpose", "ending")


def read_table(path: Optional[str]) -> Optional[Dict[str, List[Any]]]:
    """A CSV table saltus wrote, as columns: numbers where every cell reads as one (empty:
    NaN), text otherwise; None for no path."""
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


def import_xarray():
    """The xarray module; an ImportError saying how to install it when it is missing."""
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


def variable(xr, dims, values, name):
    """An xarray Variable of the column ``name``, with its ``units`` where :data:`UNITS` has them."""
    attrs = {"units": UNITS[name]} if name in UNITS else {}
    return xr.Variable(dims, values, attrs=attrs)


def result_dataset(result) -> Any:
    """:meth:`saltus.Result.to_xarray`."""
    xr = import_xarray()
    prof = result.profiles
    z = prof.get("z")
    data: Dict[str, Any] = {}
    coords: Dict[str, Any] = {}
    if z is not None:
        coords["z"] = variable(xr, ("z",), z, "z")
        for k, v in prof.items():
            if k != "z":
                data[k] = variable(xr, ("z",), v, k)
    ts = result.timeseries
    if ts and "t" in ts:
        coords["t"] = variable(xr, ("t",), ts["t"], "t")
        for k, v in ts.items():
            if k != "t":
                data[f"{k}_t"] = variable(xr, ("t",), v, k)
    snaps = result.snapshots
    if snaps and z is not None and all(len(s.get("z", [])) == len(z) for _, s in snaps):
        coords["t_snapshot"] = variable(xr, ("t_snapshot",), np.array([t for t, _ in snaps]), "t")
        for k in prof:
            if k != "z" and all(k in s for _, s in snaps):
                data[f"{k}_snapshot"] = variable(xr, ("t_snapshot", "z"), np.stack([s[k] for _, s in snaps]), k)
    attrs = {"ending": result.ending, "scene_toml": result.scene_toml, "summary_json": json.dumps(result.summary)}
    attrs.update(_attrs_of(result.summary, "summary_"))
    return xr.Dataset(data, coords=coords, attrs=attrs)
