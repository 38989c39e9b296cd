"""Runs and checks of scenes, and the diagnosis of a run's folder: ``saltus run``,
``saltus check`` and ``saltus diagnose`` in this process, with the run's last state as a
:class:`Result`.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple, Union

import numpy as np

from . import _native, _outputs

PathLike = Union[str, "os.PathLike[str]"]
#: ``set=``: a dict of key -> value (values are Python values that map to TOML: bool,
#: int, float, str, dict, list), or a list of ``"KEY=VALUE"`` strings exactly as on the
#: command line.
Overrides = Union[Mapping[str, Any], Iterable[str], None]


class SaltusWarning(UserWarning):
    """Something a run met that did not fail it (reference data that cannot be read, a
    figure that cannot be drawn): the warning the command line prints on stderr."""


@dataclass(frozen=True, repr=False)
class Result:
    """The last state of a run, whatever its ending, as it was written to ``out``.

    Attributes:
        ending: ``"steady"``, ``"end_time"``, ``"max_steps"`` or ``"unstable"`` (an
            interrupted run raises instead, see :func:`run`).
        summary: the content of ``summary.json`` (``qs_star``, ``shields``, ``steps``, ...;
            keys the run did not measure are absent, as in the file).
        profiles: column name -> float64 array over the cells, ``z`` first, in the column
            order of ``profiles.csv``. Full precision (the CSV rounds to 11 significant
            digits); a value the solver has none for is NaN in memory and ``NaN`` in the
            CSV.
        text: the paragraph the command line prints.
        out: the output folder, or None when the run went to a temporary folder
            (``out=False``).
        wall: wall-clock time of the solve (s).
        figure: ``profiles.png`` in ``out``, when drawn (None with ``out=False``).
        breakdown: for an unstable run, where it broke down: ``time``, ``place``
            (``{"kind": "cell", "index", "z"}``, ``{"kind": "particle", "index"}`` or
            ``{"kind": "column"}``), ``field``, ``value``, ``reason``; else None.
        scene_toml: the resolved scene (``scene.toml``): running it reproduces the run.
        warnings: what did not fail the run, also issued as :class:`SaltusWarning`.
        timeseries: column name -> array of ``timeseries.csv`` (``t`` first; an empty
            cell is NaN).
        snapshots: the profile snapshots (``output.snapshot_interval``): (time,
            column name -> array) in time order.
    """

    ending: str
    summary: Dict[str, Any]
    profiles: Dict[str, np.ndarray]
    text: str
    out: Optional[Path]
    wall: float
    figure: Optional[Path] = None
    breakdown: Optional[Dict[str, Any]] = None
    scene_toml: str = ""
    warnings: List[str] = field(default_factory=list)
    timeseries: Dict[str, np.ndarray] = field(default_factory=dict)
    snapshots: List[Tuple[float, Dict[str, np.ndarray]]] = field(default_factory=list)

    def to_xarray(self) -> "Any":
        """The run as an xarray Dataset: the profiles on ``z``, the time series on ``t``
        (``<column>_t``), the snapshots on ``(t_snapshot, z)`` (``<column>_snapshot``),
        units in each variable's ``units`` attribute; the ending, the summary (each
        number as ``summary_<field>``, the whole as ``summary_json``) and the resolved
        scene (``scene_toml``) as attributes. Raises ImportError without xarray."""
        return _outputs.result_dataset(self)

    def to_netcdf(self, path: PathLike, **kwargs: Any) -> None:
        """:meth:`to_xarray` written to a netCDF file (``xarray.Dataset.to_netcdf``)."""
        self.to_xarray().to_netcdf(path, **kwargs)

    def to_dataframe(self) -> "Any":
        """The profiles as a pandas DataFrame, one row per cell, one column per profile.

        Raises ImportError when pandas is not installed.
        """
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError(
                "saltus.Result.to_dataframe() needs pandas, which is not installed: "
                "pip install pandas (or pip install 'saltus[pandas]')"
            ) from e
        return pd.DataFrame({k: v for k, v in self.profiles.items()})

    @property
    def profiles_df(self) -> "Any":
        """:meth:`to_dataframe`."""
        return self.to_dataframe()

    def __repr__(self) -> str:
        qs = self.summary.get("qs_star")
        qs_text = f", qs*={qs:.4g}" if isinstance(qs, float) else ""
        return (
            f"<saltus.Result {self.summary.get('scene', '')!r} {self.ending} at "
            f"t={self.summary.get('sim_time_s', float('nan')):.6g} s{qs_text}, "
            f"{len(next(iter(self.profiles.values()), []))} cells, out={self.out}>"
        )


def fspath(p: PathLike, what: str) -> str:
    """``os.fspath(p)``; a TypeError naming the argument ``what`` when p is not a path."""
    try:
        return os.fspath(p)
    except TypeError:
        raise TypeError(f"{what}: expected a path (str or os.PathLike), found {type(p).__name__}") from None


def import_modules(paths: List[str]) -> None:
    """Import the Python files or modules a scene's ``[python] modules`` names (absolute
    paths, as the scene loader resolves them), each once per process: a file is executed
    as a module named after its path, a dotted name is imported. Registering again on a
    second import is harmless (a registration replaces one of the same name)."""
    import importlib
    import importlib.util
    import sys
    from pathlib import Path

    for p in paths:
        if p.endswith(".py") or "/" in p or "\\" in p:
            path = Path(p)
            key = "saltus_scene_module_" + "".join(c if c.isalnum() else "_" for c in str(path))
            if key in sys.modules:
                continue
            spec = importlib.util.spec_from_file_location(key, path)
            if spec is None or spec.loader is None:
                raise ImportError(f"{path}: not a Python file")
            module = importlib.util.module_from_spec(spec)
            sys.modules[key] = module
            try:
                spec.loader.exec_module(module)
            except BaseException:
                del sys.modules[key]
                raise
        else:
            importlib.import_module(p)


def raise_with(interrupt: BaseException, result: Any) -> None:
    """Raise the exception a Python signal handler raised during a run (Ctrl-C's
    KeyboardInterrupt), with the run's result as its ``result`` attribute where the
    exception takes one."""
    try:
        interrupt.result = result  # type: ignore[attr-defined]
    except (AttributeError, TypeError):
        pass
    raise interrupt


def run(
    scene: PathLike,
    set: Overrides = None,
    out: Union[PathLike, None, bool] = None,
    quiet: bool = True,
    restart: Optional[PathLike] = None,
    closures: Optional[PathLike] = None,
    warm_start: Optional[PathLike] = None,
) -> Result:
    """Run a scene, as ``saltus run SCENE --set K=V ... --out DIR``.

    Args:
        scene: the scene file (str or os.PathLike).
        set: overrides applied in order, with the command line's ``--set`` semantics
            (dotted keys; a table value replaces the whole table, so
            ``{"closures.drag": {"type": "stokes"}}`` switches the model): a dict
            ``{"physics.slope": 0.02, "solver.type": "lagrangian"}`` whose values are
            Python values written as TOML, or a list of ``"KEY=VALUE"`` strings taken
            as on the command line (``'closures.drag={type="stokes"}'``).
        out: the output folder; None (default) as the command line: the scene's
            ``output.dir``, else ``out/<meta.name>``, relative to the current folder.
            ``False``: a temporary folder, removed before returning (the Result keeps
            everything in memory; ``Result.out`` and ``Result.figure`` are None).
        quiet: False shows the command line's progress on stderr (a bar on a terminal,
            else a line every 30 s) and prints the summary paragraph.
        restart: a folder holding a DEM checkpoint (``checkpoint.bin``, written at
            every interrupt and every ``output.checkpoint_interval``): the run continues
            from it, bit-identically to a run that was never stopped, as
            ``saltus run SCENE --restart DIR``.
        closures: a closures file (``[closures.<family>]`` tables, such as the
            ``fitted.toml`` of :func:`diagnose` with ``fit=True``) whose tables replace the
            scene's, family by family, before ``set``; as ``saltus run SCENE --closures
            FILE``. The resolved scene records it in ``meta.closures_file``.
        warm_start: the folder of a finished run whose final state the run starts from,
            as ``saltus run SCENE --warm-start DIR``: an Eulerian scene from its
            profiles; a DEM scene from the grains of its checkpoint (and its fluid column
            under the same forcing), or from a two-fluid run's velocities after its own
            deposition (docs/lagrangian.md, "Warm starts"). Refused (SceneError) with
            ``restart``, or when the folder holds no state the scene can take.

    Returns:
        the :class:`Result` of the last state, written to ``out`` (``profiles.csv``,
        ``summary.json``, ``scene.toml``, ``manifest.json``, ``profiles.png``).
        An unstable run returns too (``ending == "unstable"``, the last good state, the
        breakdown in ``Result.breakdown`` and ``summary["error"]``), as the command line
        writes it and exits 3: check ``result.ending``.

    Raises:
        SceneError: the scene does not load, or its solver cannot start on it.
        RunError: the outputs cannot be written.
        KeyboardInterrupt: Ctrl-C (SIGINT) during the run: the run stops after its
            current unit of work (within 0.2 s of wall time), writes the state of that
            time (``ending = "interrupted"`` in summary.json), then the exception is
            raised with that Result as its ``result`` attribute. Any exception a Python
            signal handler raises stops the run the same way.

    The run itself holds no GIL: other Python threads go on meanwhile.
    """
    scene_path = fspath(scene, "scene")
    import_modules(_native.scene_modules(scene_path, set))  # the scene's [python] modules
    from_dir = None if restart is None else fspath(restart, "restart")
    cl = None if closures is None else fspath(closures, "closures")
    warm = None if warm_start is None else fspath(warm_start, "warm_start")
    if out is False:
        with tempfile.TemporaryDirectory(prefix="saltus-") as tmp:
            raw = _native.run(scene_path, set, tmp, quiet, from_dir, cl, warm)
            series, snaps = _outputs.read_outputs(Path(tmp))
            raw["out"] = None
            raw["figure"] = None
    else:
        raw = _native.run(scene_path, set, None if out is None else fspath(out, "out"), quiet, from_dir, cl, warm)
        series, snaps = _outputs.read_outputs(Path(raw["out"]))
    interrupt = raw.pop("interrupt")
    result = Result(
        ending=raw["ending"],
        summary=raw["summary"],
        profiles=raw["profiles"],
        text=raw["text"],
        out=None if raw["out"] is None else Path(raw["out"]),
        wall=raw["wall"],
        figure=None if raw["figure"] is None else Path(raw["figure"]),
        breakdown=raw["breakdown"],
        scene_toml=raw["scene_toml"] or "",
        warnings=list(raw["warnings"]),
        timeseries=series,
        snapshots=snaps,
    )
    for w in result.warnings:
        warnings.warn(w, SaltusWarning, stacklevel=2)
    if not quiet:
        print(result.text)
        if result.out is not None:
            print(f"outputs: {result.out}")
    if interrupt is not None:
        raise_with(interrupt, result)
    return result


def diagnose(
    run_dir: PathLike,
    closures: Union[str, Iterable[str], None] = None,
    *,
    fit: bool = False,
    phi_min: float = 0.1,
    z_min: Optional[float] = None,
    z_max: Optional[float] = None,
    out: Optional[PathLike] = None,
    pool: Iterable[PathLike] = (),
) -> Dict[str, Any]:
    """Hold granular closures against a run's averaged fields, as ``saltus diagnose
    RUN_DIR [--fit] [--closures C]... [--pool DIR]... [--z-min Z --z-max Z]``
    (docs/diagnostics.md).

    Args:
        run_dir: the run's output folder (``profiles.csv`` and ``scene.toml``).
        closures: closures to evaluate instead of the scene's: TOML text or a file, or a
            list of them (``--closures``).
        fit: fit the closures' parameters (with standard errors) and write them as closure
            tables to ``OUT/fitted.toml``, for :func:`run` with ``closures=``.
        phi_min: only cells with phi above this are used.
        z_min, z_max: the fits' window of cell centres (m).
        out: output folder (default ``RUN_DIR/diagnose``).
        pool: further runs of the same scene (other seeds) whose cells are pooled.

    Returns:
        a dict: ``text`` (the table the command prints), ``out``, ``files``,
        ``warnings``, ``fitted`` (the path of ``fitted.toml``, None when no fit was
        supported or ``fit`` is False) and ``fits`` (None without ``fit``): ``phi_min``,
        ``z_min``, ``z_max``, ``viscosity`` (the fluid-phase viscosity exponent of Fry et al.
        eqs 50-51 with its errors, or why the run does not measure it), and ``closures``, one per closure: ``closure``, ``model``, ``table`` (the
        fitted closure table), ``unsupported`` and ``quantities``, each with ``quantity``,
        ``held``, ``kept`` and ``attempts``: the fits tried, full first, each either
        ``values``, ``stderr``, ``stderr_independent``, ``cells``, ``residual_rms`` or the
        ``reason`` the cells cannot support it.

    Raises:
        SceneError: a missing folder or file, a column a comparison needs, a bad
            ``closures`` value.
    """
    if closures is None:
        cl: List[str] = []
    elif isinstance(closures, (str, os.PathLike)):
        cl = [os.fspath(closures)]
    else:
        cl = [os.fspath(c) for c in closures]
    return _native.diagnose(
        fspath(run_dir, "run_dir"),
        cl,
        float(phi_min),
        bool(fit),
        z_min,
        z_max,
        None if out is None else fspath(out, "out"),
        [fspath(p, "pool") for p in pool],
    )


def check(
    scene: PathLike, set: Overrides = None, *, toml: bool = False, closures: Optional[PathLike] = None
) -> Union[Dict[str, Any], str]:
    """Check a scene as ``saltus check SCENE --set K=V ...``: parse it, fill every default,
    check ranges and closure needs and set up its solver without running it.

    Returns the resolved scene (every default filled in, the one ``scene.toml`` of a run
    holds) as a dict, or as its TOML text with ``toml=True``. ``closures``: a closures
    file whose tables replace the scene's, as in :func:`run` (refused as ``run`` refuses it).

    Raises:
        SceneError: with the command line's message, and ``file`` and ``key`` attributes.
    """
    import_modules(_native.scene_modules(fspath(scene, "scene"), set))  # [python] modules
    cl = None if closures is None else fspath(closures, "closures")
    resolved, text = _native.check(fspath(scene, "scene"), set, cl)
    return text if toml else resolved
