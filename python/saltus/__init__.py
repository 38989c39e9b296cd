"""saltus from Python: run scenes, check them, evaluate closures, list models.

The same program as the ``saltus`` command line, bound through pyo3: one scene loader
(with the ``--set`` overrides), one run driver, one closure evaluator, one model listing.
Every number comes from the Rust library; this module converts arguments and results.

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

import os
import tempfile
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple, Union

import numpy as np

from . import _native, _study
from ._native import RunError, SceneError
from ._study import CalibrationResult, CompareResult, SweepResult, calibrate, check_calibration, compare, sweep
from . import closures as _closures
from .posterior import PosteriorResult, posterior
from .closures import register_fluctuation, register_kinetic_theory, register_mixing_length, register_rheology

__all__ = [
    "run",
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
        return _study.result_dataset(self)

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


def _path(p: PathLike, what: str) -> str:
    try:
        return os.fspath(p)
    except TypeError:
        raise TypeError(f"{what}: expected a path (str or os.PathLike), found {type(p).__name__}") from None


def run(
    scene: PathLike,
    set: Overrides = None,
    out: Union[PathLike, None, bool] = None,
    quiet: bool = True,
    restart: Optional[PathLike] = None,
    closures: Optional[PathLike] = None,
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
    scene_path = _path(scene, "scene")
    _closures.import_modules(_native.scene_modules(scene_path, set))  # the scene's [python] modules
    from_dir = None if restart is None else _path(restart, "restart")
    cl = None if closures is None else _path(closures, "closures")
    if out is False:
        with tempfile.TemporaryDirectory(prefix="saltus-") as tmp:
            raw = _native.run(scene_path, set, tmp, quiet, from_dir, cl)
            series, snaps = _study.read_outputs(Path(tmp))
            raw["out"] = None
            raw["figure"] = None
    else:
        raw = _native.run(scene_path, set, None if out is None else _path(out, "out"), quiet, from_dir, cl)
        series, snaps = _study.read_outputs(Path(raw["out"]))
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
        try:
            interrupt.result = result
        except (AttributeError, TypeError):
            pass
        raise interrupt
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
        _path(run_dir, "run_dir"),
        cl,
        float(phi_min),
        bool(fit),
        z_min,
        z_max,
        None if out is None else _path(out, "out"),
        [_path(p, "pool") for p in pool],
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
    _closures.import_modules(_native.scene_modules(_path(scene, "scene"), set))  # [python] modules
    cl = None if closures is None else _path(closures, "closures")
    resolved, text = _native.check(_path(scene, "scene"), set, cl)
    return text if toml else resolved


def models(family: Optional[str] = None) -> List[Dict[str, Any]]:
    """Every registered closure model, as ``saltus models [FAMILY] --json``: a list of
    ``{"family", "name", "equation", "source", "parameters": [{"name", "default",
    "range", "unit", "doc"}]}``. Closures registered with :func:`register_closure` come
    after the built-in ones, with ``"runtime": True``.

    Args:
        family: ``drag``, ``hindrance``, ``viscosity``, ``granular``, ``turbulence`` or
            ``fluctuation``; None for all.

    Raises:
        ValueError: an unknown family (the message lists the known ones).
    """
    return _native.models(family)


class Closure:
    """One closure model, evaluated on arrays as ``saltus closure eval`` does on a CSV.

    Args:
        family: ``drag``, ``hindrance``, ``viscosity``, ``granular`` (local rheologies:
            mu_i, mu_k), ``kinetic_theory`` (the coefficients of a
            ``frictional_collisional`` table, whose ``type`` may be left out),
            ``turbulence`` or ``fluctuation``.
        model: the model's table, as in a scene's ``[closures.<family>]``: a dict
            ``{"type": "richardson_zaki", "exponent": 4.65}`` or TOML text
            (``'type = "stokes"'`` or ``'{type = "stokes"}'``).
        seed: seed of the fluctuation draws (row i uses stream i of the seed), as
            ``--seed``.

    Inputs and outputs per family (the CSV columns of ``saltus closure eval --help``):

    ==============  ==================================================  ==================================
    family          inputs                                              outputs
    ==============  ==================================================  ==================================
    drag            re_p                                                cd
    hindrance       phi, re_p (interstitial Reynolds number)            factor
    viscosity       phi                                                 nu_ratio
    granular        i (mu_i) or k (mu_k)                                mu, phi
    kinetic_theory  phi                                                 g0, f1, f2, f3, f4, e_eff
    turbulence      z, phi, dudz, d (cells of one column from the       l_m, nu_t
                    bottom wall, z increasing; d one grain diameter)
    fluctuation     k, omega, nu_t, reynolds_stress, slip,              diffusivity, u_x, u_y, u_z,
                    response_time, depth, bulk_velocity (absent: 0,     duration
                    except those the model needs)
    ==============  ==================================================  ==================================

    Raises:
        SceneError: the table does not load (unknown model or key, out-of-range value,
            TOML syntax), with ``file`` = ``"saltus.Closure"`` and the key path under the
            family (``drag.type``).
        ValueError: an unknown family.
    """

    def __init__(self, family: str, model: Union[Mapping[str, Any], str], *, seed: int = 0) -> None:
        if isinstance(model, Mapping) and not isinstance(model, dict):
            model = dict(model)
        self._native = _native.Closure(family, model)
        self.seed = int(seed)

    @property
    def family(self) -> str:
        """The family, as given."""
        return self._native.family

    @property
    def name(self) -> str:
        """The model's registered name (its ``type``)."""
        return self._native.name

    @property
    def input_names(self) -> List[str]:
        """Every input name the family reads."""
        return list(self._native.input_names)

    @property
    def output_names(self) -> List[str]:
        """The names :meth:`evaluate` returns, in order."""
        return list(self._native.output_names)

    def describe(self) -> Dict[str, Any]:
        """The model as ``saltus models --json`` lists it (family, name, equation, source,
        parameters), each parameter with its configured ``value`` beside its ``default``."""
        return self._native.describe()

    @property
    def params(self) -> List[Dict[str, Any]]:
        """The model's parameters: ``name``, ``value``, ``default``, ``range``, ``unit``,
        ``doc`` (nested tables as dotted names, ``g0.a0``)."""
        return self.describe()["parameters"]

    def evaluate(self, *, seed: Optional[int] = None, **inputs: Any) -> Dict[str, np.ndarray]:
        """Evaluate on arrays named like the CSV columns; returns name -> float64 array.

        Inputs broadcast against each other as numpy arrays do (scalars included); the
        outputs have the broadcast shape. Values must be finite. An input name the
        family does not read is refused (a misspelt optional input would silently be 0).

        Args:
            seed: overrides the closure's seed for this call (fluctuation draws).

        Raises:
            TypeError: an input name the family does not read.
            ValueError: a missing input, a value out of its range (phi in [0, 1), re_p >=
                0), a non-finite value; the command line's message with rows counted
                from 0 over the flattened broadcast arrays.
        """
        accepted = set(self._native.input_names)
        unknown = [k for k in inputs if k not in accepted]
        if unknown:
            raise TypeError(
                f"Closure({self.family!r}).evaluate: unknown input {', '.join(map(repr, unknown))}; "
                f"family {self.family} reads {', '.join(self._native.input_names)}"
            )
        names = list(inputs)
        arrays = np.broadcast_arrays(*(np.asarray(inputs[k], dtype=np.float64) for k in names)) if names else []
        shape = arrays[0].shape if names else (0,)
        flat = {k: np.ascontiguousarray(a).reshape(-1) for k, a in zip(names, arrays)}
        out = self._native.evaluate_arrays(flat, self.seed if seed is None else int(seed))
        return {k: v.reshape(shape) for k, v in out.items()}

    def __repr__(self) -> str:
        return f"saltus.Closure({self.family!r}, {self.name!r})"


def register_closure(
    family: str,
    name: str,
    evaluate: Any,
    params: Optional[Mapping[str, Any]] = None,
    *,
    source: Optional[str] = None,
    equation: Optional[str] = None,
    limits: Optional[List[Any]] = None,
    reynolds: str = "interstitial",
    depends_on_reynolds: bool = True,
) -> None:
    """Register a closure written in Python: scenes then name it by ``type = name`` in
    ``[closures.<family>]`` (scene files and ``set=`` overrides alike), in both solvers;
    :func:`models` lists it and :func:`closure_check` checks it.

    ``evaluate`` is called with the family's inputs as keyword float64 arrays of one
    length (the names :class:`Closure` takes) and every parameter as a keyword float, and
    returns the family's outputs: a dict ``{"cd": array}``, or for one output the array
    itself, float64 of the inputs' length, every value finite.

    ==========  ====================================  ===========
    family      inputs                                outputs
    ==========  ====================================  ===========
    drag        re_p                                  cd
    hindrance   phi, re_p (interstitial Re_p)         factor
    viscosity   phi                                   nu_ratio
    ==========  ====================================  ===========

    The other families (granular, turbulence, fluctuation) are refused: their traits are
    not functions of arrays (a packing inverse solved by bisection, column views and
    transported fields, a seeded random draw per particle).

    Example, Dallavalle drag (Chassagne et al. 2023 eq 2.11a)::

        def dallavalle(re_p, cd_inf, a):
            return cd_inf + a / re_p

        saltus.register_closure("drag", "py_dallavalle", dallavalle,
            params={"cd_inf": {"default": 0.4, "range": "[0, 10]", "unit": "-",
                               "description": "C_D at infinite Re_p"},
                    "a": {"default": 24.4, "range": "(0, 100]", "unit": "-",
                          "description": "viscous coefficient"}},
            limits=[("stokes", "a"), "high_reynolds", "decreasing"])
        saltus.run("case.toml", set={"closures.drag.type": "py_dallavalle"})

    Args:
        family: ``drag``, ``hindrance`` or ``viscosity``.
        name: the ``type`` scenes use: letters, digits and ``_``, not a built-in name of
            the family. Registering a name again replaces it (a notebook cell run
            again); models already loaded keep the function they were built with.
        evaluate: the function (called once per batch the solver evaluates: a column of
            the Eulerian solver, a chunk of 256 particles of the DEM; never per cell).
        params: parameter name -> default, or -> dict of ``default``, ``range`` (an
            interval ``"(0, 100]"``, ``"[0, inf)"``, or a closed pair ``(lo, hi)``),
            ``unit`` and ``description``. A scene's value outside the range is refused,
            as an unknown key is, naming the file and the key.
        source: where the law comes from (default: the function's module and name).
        equation: the law, one line (default: the first line of the function's
            docstring).
        limits: what :func:`closure_check` verifies: ``"high_reynolds"`` (drag: C_D ->
            its value at Re_p = 1e150), ``"dilute"`` (hindrance, viscosity: -> 1 as phi
            -> 0), ``"decreasing"``, ``"increasing"``, ``("stokes", x)`` (drag: C_D Re_p
            -> x as Re_p -> 0), ``("einstein", x)`` (viscosity: 1 + x phi); x a number or
            a parameter's name.
        reynolds: hindrance only, the Reynolds number at which the drag law's C_D is
            evaluated: ``"interstitial"`` (Re_p) or ``"superficial"`` ((1 - phi) Re_p).
        depends_on_reynolds: hindrance only; False lets the DEM evaluate the factor per
            fluid cell (with re_p = 0) instead of per particle, as for the built-in
            Richardson-Zaki.

    How the solvers use it: C_D Re_p is C_D(r) r at r = max(Re_p, 1e-12) (finite at
    rest); C_D^inf is C_D at Re_p = 1e150, taken when the scene loads. Python is entered
    with the GIL held for each batch: a run with such a closure is not parallel in it.

    Raises:
        ValueError: an unknown or refused family, a name that is not usable, a default
            outside its range, an unknown limit.
        TypeError: ``evaluate`` is not callable, a parameter is not a number.

    During a run, an exception raised by ``evaluate``, or outputs of the wrong shape or
    dtype or not finite, end the run: :func:`run` raises :class:`RunError` with the
    message (the exception's included).
    """
    if source is None:
        module = getattr(evaluate, "__module__", None) or "?"
        qualname = getattr(evaluate, "__qualname__", None) or type(evaluate).__name__
        source = f"Python function {module}.{qualname}"
    if equation is None:
        doc = (getattr(evaluate, "__doc__", None) or "").strip()
        equation = doc.splitlines()[0].strip() if doc else "Python function (no docstring)"
    if params is not None and not isinstance(params, dict):
        params = dict(params)
    _native.register_closure(
        family, name, evaluate, params, source, equation, limits, reynolds, bool(depends_on_reynolds)
    )


def unregister_closure(family: str, name: str) -> bool:
    """Remove a closure registered with :func:`register_closure`; whether there was one.
    Scenes loaded afterwards no longer know the name; models already loaded keep it.

    Raises:
        ValueError: an unknown family.
    """
    return _native.unregister_closure(family, name)


@dataclass(frozen=True, repr=False)
class CheckReport:
    """The report of :func:`closure_check`.

    Attributes:
        family, model: what was checked.
        passed: whether every check passed (``bool(report)`` too).
        text: the report the command line prints.
        outcomes: one dict per check: ``name``, ``passed``, ``summary`` and, on a
            failure, ``input`` (the smallest failing input found), else None.
    """

    family: str
    model: str
    passed: bool
    text: str
    outcomes: List[Dict[str, Any]]

    def __bool__(self) -> bool:
        return self.passed

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        failed = sum(not o["passed"] for o in self.outcomes)
        return f"<saltus.CheckReport {self.family} {self.model!r}: {failed} of {len(self.outcomes)} checks failed>"


def closure_check(family: str, model: Union[Mapping[str, Any], str], *, cases: int = 256) -> CheckReport:
    """The generic property checks of ``saltus closure check --family F --model TOML`` on a
    closure, built-in or registered with :func:`register_closure`: parameters documented
    with unit and range, TOML round trip, finite outputs over the parameter and input
    ranges, batch equal to scalar bit for bit, each declared limit; a failing case shrunk
    to the smallest input found.

    Args:
        family: the scene family (``drag``, ``hindrance``, ...).
        model: the closure table with its ``type``, a dict or TOML text.
        cases: random cases per property check.

    Raises:
        SceneError: the table does not load (unknown model or key, value out of range).
    """
    if isinstance(model, Mapping) and not isinstance(model, dict):
        model = dict(model)
    raw = _native.closure_check(family, model, int(cases))
    return CheckReport(
        family=raw["family"], model=raw["model"], passed=raw["passed"], text=raw["text"], outcomes=raw["outcomes"]
    )
