"""Several seeds of a DEM scene as one answer: ``saltus run SCENE --seeds N`` in this
process, read back from the ``seeds.json`` it writes."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

from . import _native
from ._run import Overrides, PathLike, fspath, import_modules, raise_with


@dataclass(frozen=True, repr=False)
class SeedsResult:
    """The pooled answer of several seeds and each seed's run, as written to ``out``.

    Attributes:
        ending: the seeds' ending when they agree (``"target_error"`` when the pooled
            rule stopped them, ``"end_time"``, ``"interrupted"``, ...), else ``"mixed"``.
        qs, qs_stderr: the pooled transport rate (m^2/s) of the seeds' averaging windows
            and its standard error (the larger of the within-seed and between-seed
            estimates); None without a window in every seed.
        qs_star, qs_star_stderr: the same as qs*.
        pooled: the pooling's details as in ``seeds.json`` (``mean``, ``stderr``,
            ``stderr_within``, ``stderr_between``, ``relative_error``, ...), or None.
        target_error: the scene's ``solver.lagrangian.target_error``, if any.
        cpu_time_s: the seeds' CPU time together (s).
        runs: one dict per seed, in seed order: ``seed``, ``dir`` (its output folder),
            ``ending``, ``error`` (None when it ran), ``sim_time_s``, ``cpu_time_s``,
            ``window_start_s``, ``qs_window``, ``qs_window_stderr``, and ``summary``
            (its ``summary.json``, or None when it wrote none).
        errors: (seed, message) of each seed that failed.
        text: the paragraph the command line prints.
        out: the output folder; file: its ``seeds.json``.
    """

    ending: str
    qs: Optional[float]
    qs_stderr: Optional[float]
    qs_star: Optional[float]
    qs_star_stderr: Optional[float]
    pooled: Optional[Dict[str, Any]]
    target_error: Optional[float]
    cpu_time_s: float
    runs: List[Dict[str, Any]]
    text: str
    out: Path
    file: Path
    errors: List[Any] = field(default_factory=list)

    def __repr__(self) -> str:
        q = "-" if self.qs_star is None else f"{self.qs_star:.5g} +- {self.qs_star_stderr:.2g}"
        return f"SeedsResult({len(self.runs)} seeds, ending {self.ending!r}, qs* {q}, out={str(self.out)!r})"


def run_seeds(
    scene: PathLike,
    seeds: int,
    set: Overrides = None,
    out: Optional[PathLike] = None,
    quiet: bool = True,
    closures: Optional[PathLike] = None,
    warm_start: Optional[PathLike] = None,
) -> SeedsResult:
    """Run ``seeds`` seeds of a DEM scene in parallel as one answer, as
    ``saltus run SCENE --seeds N --out DIR``: seeds ``seed`` .. ``seed + N - 1`` of the
    scene, each in ``out/seed_<k>/``, stopped together when their pooled transport rate
    has the scene's ``solver.lagrangian.target_error`` (or at ``end_time``), and
    ``out/seeds.json`` with the pooled answer.

    Args:
        scene, set, closures: as :func:`run`.
        seeds: the number of seeds, 1 to the command line's limit.
        out: the output folder; None: the scene's ``output.dir``, else ``out/<meta.name>``.
        quiet: False prints the paragraph of the pooled answer.
        warm_start: the folder of a developed state every seed starts from (seeds of a
            scene with random draws only), or of a run of at least ``seeds`` seeds,
            whose ``seed_<k>/`` states start one seed each (docs/lagrangian.md, "Warm
            starts").

    Returns:
        the :class:`SeedsResult` read back from ``seeds.json`` and the seeds' summaries.
        A seed that failed is in ``errors`` and has ``error`` in its row; the others'
        outputs are kept.

    Raises:
        SceneError: the scene does not load, is not a DEM scene, or a warm start it cannot
            take; ValueError/RunError: ``seeds`` out of range, or the outputs cannot be
            written.
        KeyboardInterrupt: Ctrl-C (SIGINT) during the runs: every seed stops after its
            current unit of work with its state written (``ending = "interrupted"``),
            ``seeds.json`` is written, then the exception is raised with the
            SeedsResult as its ``result`` attribute.

    The runs hold no GIL: other Python threads go on meanwhile.
    """
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise ValueError(f"seeds = {seeds!r}: a whole number of seeds, at least 1")
    scene_path = fspath(scene, "scene")
    import_modules(_native.scene_modules(scene_path, set))
    raw = _native.run_seeds(
        scene_path,
        seeds,
        set,
        None if out is None else fspath(out, "out"),
        quiet,
        None if closures is None else fspath(closures, "closures"),
        None if warm_start is None else fspath(warm_start, "warm_start"),
    )
    interrupt = raw.pop("interrupt")
    file = Path(raw["file"])
    doc = json.loads(file.read_text())
    runs = []
    for row in doc["runs"]:
        summary_file = Path(row["dir"]) / "summary.json"
        row = dict(row, summary=json.loads(summary_file.read_text()) if summary_file.is_file() else None)
        runs.append(row)
    result = SeedsResult(
        ending=doc["ending"],
        qs=doc.get("qs"),
        qs_stderr=doc.get("qs_stderr"),
        qs_star=doc.get("qs_star"),
        qs_star_stderr=doc.get("qs_star_stderr"),
        pooled=doc.get("pooled"),
        target_error=doc.get("target_error"),
        cpu_time_s=doc.get("cpu_time_s", 0.0),
        runs=runs,
        text=raw["text"],
        out=Path(raw["out"]),
        file=file,
        errors=[tuple(e) for e in raw["errors"]],
    )
    if interrupt is not None:
        raise_with(interrupt, result)
    return result
