"""The closure models from Python: the listing of every registered model
(``saltus models``), one model evaluated on arrays (``saltus closure eval``) and the
property checks of a model (``saltus closure check``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Union

import numpy as np

from . import _native


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
