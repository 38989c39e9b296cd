"""Closures written in Python: each function registers a model that scenes then name by
``type = name`` in ``[closures.<family>]``, in both solvers.

:func:`register_closure` registers a drag, hindrance, viscosity or side-wall friction law
(one function of arrays; :func:`unregister_closure` removes it); the other functions
register the granular, turbulence and fluctuation families. Every face is a numpy
function called once per batch the solver evaluates, with named float64 arrays in and
named float64 arrays out; the parameters (``params=``, as for :func:`register_closure`)
and the face's scalar keywords are passed as keyword floats.

=====================  =========================  ==========================  =====================================
function               inputs (arrays)            outputs                     keywords (floats)
=====================  =========================  ==========================  =====================================
rheology               ``i``, ``j`` or ``k``      ``mu``, ``phi``             diameter, density, restitution, friction
rheology ``inverse``   ``phi``                    ``i``, ``j`` or ``k``       idem
kinetic theory         ``phi``, ``sqrt_t``,       ``g0``, ``f1``-``f4``,      idem
                       ``k_drag``                 ``e_eff``
mixing length          ``z``, ``dz``, ``phi``,    ``l_m``                     diameter, nu_f
                       ``dudz``
fluctuation draw       ``k``, ``omega``, ``nu_t``,  ``u_x``, ``u_y``, ``u_z``,  depth, bulk_velocity
                       ``reynolds_stress``,       ``duration``
                       ``slip``, ``response_time``
                       + the variates
fluctuation            ``k``, ``omega``, ``nu_t``,  ``diffusivity``             depth, bulk_velocity
``diffusivity``        ``reynolds_stress``
=====================  =========================  ==========================  =====================================

``limits=`` declares what :func:`saltus.closure_check` verifies beside its generic checks
(the failing input shrunk to the smallest found): rheology ``("static_friction", x)`` (mu
-> x as the control number -> 0, and mu = x at 0; x a number or a parameter's name),
``"packing_decreasing"`` (phi non-increasing in the control number), ``"increasing"`` (mu
non-decreasing); kinetic theory ``"dilute"`` (g0 -> 1 as phi -> 0); mixing length
``("wall_length", x)`` (l_m / z -> x as z -> 0 in clear fluid, the law of the wall
l_m = kappa z); fluctuation ``"non_negative"`` (diffusivity D >= 0).

The grain keywords are those of the scene's ``[particles]`` (outside a scene, in
:class:`saltus.Closure` and :func:`saltus.closure_check`: the glass beads of Chassagne et
al. 2023, d = 6 mm, rho_p = 2500 kg/m^3, e = 0.7, mu_p = 0.4). A function returning a
dict of arrays may also return the single array of a one-output face.

Errors: an exception raised by a face during a run, or an output of the wrong shape or
dtype or not finite (a draw's ``duration`` may be +inf: no fluctuation yet; the
kinetic-theory ``g0`` and ``f1``-``f4`` may be +inf where phi > 0, their divergence at the
packing where g0 diverges, as the built-in ``frictional_collisional`` from ``phi_max`` on),
ends the run:
:func:`saltus.run` raises :class:`saltus.RunError` whose message names the family, the
closure, the output and the input where it went wrong, with ``file`` the scene and
``key`` the closure's table (``closures.granular``).
"""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence

from . import _native

__all__ = [
    "register_closure",
    "unregister_closure",
    "register_rheology",
    "register_kinetic_theory",
    "register_mixing_length",
    "register_fluctuation",
]


def _described(function: Any, source: Optional[str], equation: Optional[str]) -> "tuple[str, str]":
    # where not given: the function's module and name, the first line of its docstring
    if source is None:
        module = getattr(function, "__module__", None) or "?"
        qualname = getattr(function, "__qualname__", None) or type(function).__name__
        source = f"Python function {module}.{qualname}"
    if equation is None:
        doc = (getattr(function, "__doc__", None) or "").strip()
        equation = doc.splitlines()[0].strip() if doc else "Python function (no docstring)"
    return source, equation


def _params(params: Optional[Mapping[str, Any]]) -> Optional[Dict[str, Any]]:
    return None if params is None else dict(params)


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
    source, equation = _described(evaluate, source, equation)
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


def register_rheology(
    name: str,
    friction_packing: Callable[..., Mapping[str, Any]],
    params: Optional[Mapping[str, Any]] = None,
    *,
    control: str = "i",
    inverse: Optional[Callable[..., Any]] = None,
    source: Optional[str] = None,
    equation: Optional[str] = None,
    limits: Optional[Sequence[Any]] = None,
) -> None:
    """Register a granular local rheology: friction mu = tau_p / p_p and volume fraction
    phi as functions of a control number, the ``[closures.granular]`` of a scene.

    ``friction_packing(<control>=x, **params, diameter, density, restitution, friction)``
    returns ``{"mu": ..., "phi": ...}`` on the control numbers x >= 0 (+inf included: the
    free-flight limit of a state sheared at zero pressure). The solver computes the
    control number from the local state (``control``: ``"i"`` the inertial number
    d |gamma_dot| / sqrt(p / rho_p), ``"j"`` the viscous number eta_f |gamma_dot| / p,
    ``"k"`` = J + alpha I^2 with ``alpha`` a parameter the model must declare) and the
    pressure at which a sheared state reaches a control number (closed forms).

    ``inverse(phi=..., **params, <grain keywords>)``, optional, returns the control
    number at which the packing law gives phi (0 at or above the jammed packing, +inf at
    phi <= 0), the shear-induced pressure of the Eulerian solver. Without it the solver
    bisects on arrays: 100 halvings of [-30, 30] in log x, one call of
    ``friction_packing`` per halving on the whole column (the packing must decrease with
    x), the arithmetic of the built-in laws without a closed form.

    ``limits``: ``("static_friction", "mu_s")``, ``"packing_decreasing"``,
    ``"increasing"`` (module docstring).

    Example, mu(I) of Chassagne et al. 2023 eqs 1.1-1.2 (the built-in ``mu_i``)::

        def mu_i(i, mu_s, mu_2, i0, phi_c, b, **grain):
            \"\"\"mu = mu_s + (mu_2 - mu_s) / (i0 / I + 1), phi = phi_c / (1 + b I)\"\"\"
            with np.errstate(divide="ignore"):
                mu = np.where(i > 0, mu_s + (mu_2 - mu_s) / (i0 / i + 1.0), mu_s)
            return {"mu": mu, "phi": phi_c / (1.0 + b * np.maximum(i, 0.0))}

        saltus.register_rheology("py_mu_i", mu_i, params={"mu_s": 0.35, ...})

    Raises:
        ValueError: a name that is not usable, an unknown control number, ``k`` without
            an ``alpha`` parameter, a parameter named as an input or keyword.
        TypeError: a function that is not callable.
    """
    source, equation = _described(friction_packing, source, equation)
    _native.register_faces(
        "local",
        name,
        {"evaluate": friction_packing, "inverse": inverse},
        _params(params),
        source,
        equation,
        None if limits is None else list(limits),
        {"control": control},
    )


def register_kinetic_theory(
    name: str,
    coefficients: Callable[..., Mapping[str, Any]],
    params: Optional[Mapping[str, Any]] = None,
    *,
    saltation: bool = False,
    drag_dissipation: str = "quadratic",
    source: Optional[str] = None,
    equation: Optional[str] = None,
    limits: Optional[Sequence[Any]] = None,
) -> None:
    """Register a frictional-collisional granular stress whose kinetic-theory
    coefficients are written in Python: p = rho_p F1 T, eta = rho_p d F2 sqrt(T),
    kappa = rho_p d F3 sqrt(T), Gamma = rho_p / d F4 T^{3/2} (Chassagne et al. 2023 eqs
    2.19-2.22, table 1), and the granular temperature equation the Eulerian solver
    advances with them.

    ``coefficients(phi=..., sqrt_t=..., k_drag=..., **params, diameter, density,
    restitution, friction)`` returns ``{"g0", "f1", "f2", "f3", "f4", "e_eff"}`` on the
    column (``e_eff`` the effective restitution F4 uses). With ``saltation=True`` the
    solver passes the saltation input of eq 3.6 (sqrt(T) and the drag coefficient K of
    eq 2.10) where it has one, 0 elsewhere (the half-cell evaluations); without, both are 0.

    The enduring-contact part is the built-in Johnson-Jackson law (eq 2.14) with its
    Coulomb friction (eq 2.15) at four parameters every such model has, declared here
    with these defaults when ``params`` does not declare them: ``p0`` = 0.05 Pa,
    ``phi_rlp`` = 0.57, ``phi_max`` = 0.635 (0 < phi_rlp < phi_max < 1), and
    ``static_friction`` = 0.146 + 0.228 tanh(0.4 / 0.232) (eq B1 at mu_p = 0.4).
    ``drag_dissipation``: ``"linear"`` (c_J = 3, eq 2.25) or ``"quadratic"`` (3 + 2
    C_D^inf / C_D, eq 3.13). ``limits``: ``"dilute"``, g0 -> 1 as phi -> 0.

    Raises:
        ValueError: an unknown ``drag_dissipation``, crossed packings (at load), a name
            that is not usable.
        TypeError: a function that is not callable.
    """
    source, equation = _described(coefficients, source, equation)
    _native.register_faces(
        "kinetic",
        name,
        {"evaluate": coefficients},
        _params(params),
        source,
        equation,
        None if limits is None else list(limits),
        {"saltation": bool(saltation), "drag_dissipation": drag_dissipation},
    )


def register_mixing_length(
    name: str,
    mixing_length: Callable[..., Any],
    params: Optional[Mapping[str, Any]] = None,
    *,
    source: Optional[str] = None,
    equation: Optional[str] = None,
    limits: Optional[Sequence[Any]] = None,
) -> None:
    """Register an algebraic turbulence closure, the ``[closures.turbulence]`` of a scene:
    the mixing length over the cells of one column, from which the solver takes the
    Prandtl eddy viscosity nu_t = l_m^2 |du/dz| (Chassagne et al. 2023 eq 2.8a) and the
    Reynolds stress nu_t du/dz, as for the built-in ``mixing_length``.

    ``mixing_length(z=..., dz=..., phi=..., dudz=..., **params, diameter, nu_f)`` returns
    ``l_m`` (m) per cell: ``z`` the cell centres from the bottom wall, ``dz`` their
    widths, ``phi`` the solid fraction, ``dudz`` the fluid shear rate; ``diameter`` the
    grain diameter, ``nu_f`` the fluid's kinematic viscosity. One call per column
    evaluation. ``limits``: ``("wall_length", "kappa")``, l_m / z -> kappa at the wall.

    Two-equation (k-omega) turbulence is not written in Python: its closure is coupled
    source terms, wall values and initial states of the fields the solver transports,
    not one function of the column; it is a compiled model (docs/extending.md).

    Raises:
        ValueError: a name that is not usable, a parameter named as an input.
        TypeError: a function that is not callable.
    """
    source, equation = _described(mixing_length, source, equation)
    _native.register_faces(
        "mixing_length",
        name,
        {"evaluate": mixing_length},
        _params(params),
        source,
        equation,
        None if limits is None else list(limits),
        {},
    )


def register_fluctuation(
    name: str,
    draw: Callable[..., Mapping[str, Any]],
    diffusivity: Callable[..., Any],
    params: Optional[Mapping[str, Any]] = None,
    *,
    variates: Optional[Mapping[str, str]] = None,
    needs: Sequence[str] = (),
    source: Optional[str] = None,
    equation: Optional[str] = None,
    limits: Optional[Sequence[Any]] = None,
) -> None:
    """Register a model of the fluid velocity fluctuations seen by particles, the
    ``[closures.fluctuation]`` of a scene: a particle face for the DEM and a mean-field
    face for the Eulerian solver.

    ``draw(k=..., omega=..., nu_t=..., reynolds_stress=..., slip=..., response_time=...,
    <variates>, **params, depth, bulk_velocity)`` returns ``{"u_x", "u_y", "u_z",
    "duration"}``: the fluctuation (m/s) and how long it holds (s; +inf: no fluctuation
    until the flow has a turnover time). ``variates`` (input name -> ``"normal"``,
    ``"exponential"`` or ``"uniform"``, at most 16) are the random numbers of the draw: the
    solver takes them, in the order given, from the particle's own seeded stream, so a
    run is bit-reproducible for a seed whatever the thread count, and a function that
    declares the variates of a built-in model in its order sees its numbers (the eddy
    interaction model ``eim``: three normals, then one exponential). The function itself
    must not draw random numbers. A chunk of draws (``Fluctuation::draw_batch``, what
    ``closure_check`` compares with one draw per point) is one call on arrays, each
    draw's variates from its own particle's stream, in the order above; the DEM calls it
    once per chunk of 256 particles per evaluation, on the particles of the chunk whose
    eddy expired (none: no call).

    ``diffusivity(k=..., omega=..., nu_t=..., reynolds_stress=..., **params, depth,
    bulk_velocity)`` returns the wall-normal particle diffusivity D >= 0 (m^2/s) on the
    column, for the Eulerian drift velocity u_d = D grad(phi) / phi (eq 4.4).

    ``limits``: ``"non_negative"``, D >= 0.

    ``needs``: the fields the model reads from the turbulence closure (``"k"``,
    ``"omega"``, ``"nu_t"``, ``"reynolds_stress"``); a scene whose turbulence closure does
    not provide one is refused at load. The others are passed as 0.

    Raises:
        ValueError: an unknown variate or field, a variate named as an input.
        TypeError: a function that is not callable or a missing ``diffusivity``.
    """
    source, equation = _described(draw, source, equation)
    _native.register_faces(
        "fluctuation",
        name,
        {"evaluate": draw, "diffusivity": diffusivity},
        _params(params),
        source,
        equation,
        None if limits is None else list(limits),
        {"variates": None if variates is None else dict(variates), "needs": list(needs)},
    )
