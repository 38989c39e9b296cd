"""Joint fits of closure constants against a reference (``saltus calibrate``) in this
process, with the report they wrote read back.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List

import numpy as np

from . import _native
from ._outputs import read_table
from ._run import fspath


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
    raw = _native.calibrate(fspath(file, "file"), set, None if out is None else fspath(out, "out"), False)
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
        evaluations=read_table(str(out_dir / "calibration.csv")) or {},
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
    return _native.calibrate(fspath(file, "file"), set, None, True)["text"]
