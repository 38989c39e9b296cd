"""Comparisons of variants of a scene (``saltus compare``) in this process, with the
tables they wrote read back as columns.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

from . import _native
from ._outputs import read_table
from ._run import fspath


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
    raw = _native.compare(fspath(file, "file"), set, None if out is None else fspath(out, "out"))
    opt = lambda p: None if p is None else Path(p)  # noqa: E731
    return CompareResult(
        out=Path(raw["out"]),
        table=read_table(raw["table"]) or {},
        precision=read_table(raw["precision"]),
        figure=opt(raw["figure"]),
        precision_figure=opt(raw["precision_figure"]),
        failures=raw["failures"],
        warnings=list(raw["warnings"]),
    )
