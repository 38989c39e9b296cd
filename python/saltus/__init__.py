"""saltus from Python: run scenes, check them, evaluate closures, list models.

The same program as the ``saltus`` command line, bound through pyo3: one scene loader
(with the ``--set`` overrides), one run driver, one closure evaluator, one model listing.
Every number comes from the Rust library; the package converts arguments and results.

>>> import saltus
>>> r = saltus.run("cases/chassagne2023/case01.toml", out=False)
>>> r.ending, round(r.summary["qs_star"], 2)
('steady', 2.53)
>>> saltus.Closure("drag", {"type": "stokes"}).evaluate(re_p=[0.1, 1.0])["cd"]
array([240.,  24.])

A closure written in Python (:func:`register_closure`) is named in scenes like a built-in
one and goes through the command line's property checks (:func:`closure_check`).

Errors: bad input raises :class:`SceneError` (a ``ValueError``) with the message the
command line prints; a run that cannot write its outputs raises :class:`RunError`.
"""

from __future__ import annotations

# Standard names the package namespace holds beside its API (saltus.os, saltus.np,
# saltus.Path, the typing names, ...); nothing below uses them.
import os  # noqa: F401
import tempfile  # noqa: F401
import warnings  # noqa: F401
from dataclasses import dataclass, field  # noqa: F401
from pathlib import Path  # noqa: F401
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple, Union  # noqa: F401

import numpy as np  # noqa: F401

from . import _native
from ._calibrate import CalibrationResult, calibrate, check_calibration
from ._compare import CompareResult, compare
from ._models import CheckReport, Closure, closure_check, models
from ._native import RunError, SceneError
from ._run import Overrides, PathLike, Result, SaltusWarning, check, diagnose, run
from ._seeds import SeedsResult, run_seeds
from ._sweep import SweepResult, sweep
from .closures import (
    register_closure,
    register_fluctuation,
    register_kinetic_theory,
    register_mixing_length,
    register_rheology,
    unregister_closure,
)
from .posterior import PosteriorResult, posterior

__all__ = [
    "run",
    "run_seeds",
    "SeedsResult",
    "compare",
    "CompareResult",
    "calibrate",
    "check_calibration",
    "CalibrationResult",
    "posterior",
    "PosteriorResult",
    "sweep",
    "SweepResult",
    "check",
    "diagnose",
    "models",
    "Closure",
    "register_closure",
    "register_rheology",
    "register_kinetic_theory",
    "register_mixing_length",
    "register_fluctuation",
    "unregister_closure",
    "closure_check",
    "CheckReport",
    "Result",
    "SceneError",
    "RunError",
    "SaltusWarning",
    "__version__",
]


__version__: str = _native.__version__
