"""A posterior sample of a calibration's constants, beside its Laplace errors.

:func:`posterior` samples exp(-chi^2 / 2) of a calibrate file (docs/calibration.md) with
the affine-invariant ensemble sampler of Goodman & Weare (2010) as ``emcee`` implements it
(Foreman-Mackey et al. 2013), uniform priors within the file's bounds and its Gaussian
priors inside chi^2. Where chi^2 is quadratic about the optimum the sample's mean is the
optimum and its covariance the Laplace approximation (J^T J)^-1 that ``saltus calibrate``
reports as ``stderr_statistical``; where the two differ, the sample is the better error.
With ``scale=True`` the likelihood is exp(-chi^2 / (2 s^2)), s = sqrt(chi^2_min / dof)
where the misfit exceeds its noise, the counterpart of the scaled ``stderr``.

Every chi^2 is one run of the model (warm from the optimum's state); the runs release the
GIL, so a thread pool of ``threads`` evaluates walkers at once. A sample is reproducible
for a seed at any thread count.
"""

from __future__ import annotations

import csv
import json
import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _native
from ._calibrate import CalibrationResult
from ._run import fspath


@dataclass
class PosteriorResult:
    """The sample of :func:`posterior` and its summary beside the Laplace approximation."""

    #: the free constants, in the calibrate file's order
    keys: List[str]
    #: the sample after the burn-in, thinned: one row per draw, one column per constant
    samples: np.ndarray
    mean: np.ndarray
    sd: np.ndarray
    #: 16th, 50th and 84th percentiles of each constant (rows in that order)
    quantiles: np.ndarray
    correlation: np.ndarray
    #: the calibration's optimum and Laplace errors (scaled as ``scale`` asks) and correlation
    optimum: np.ndarray
    laplace_sd: np.ndarray
    laplace_correlation: np.ndarray
    #: emcee's integrated autocorrelation time of each constant, in steps (NaN where the
    #: chain is too short for an estimate)
    autocorrelation: np.ndarray
    acceptance: float
    walkers: int
    steps: int
    burn: int
    thin: int
    #: model runs and wall time of the sampling
    runs: int
    wall_time_s: float
    scale: float
    files: List[Path] = field(default_factory=list)

    def table(self) -> List[Dict[str, Any]]:
        """Per constant: the optimum, Laplace error, sample mean, sd, percentiles and their
        ratios, as rows for a report."""
        return [
            {
                "key": k,
                "optimum": float(self.optimum[i]),
                "laplace_sd": float(self.laplace_sd[i]),
                "mean": float(self.mean[i]),
                "sd": float(self.sd[i]),
                "p16": float(self.quantiles[0, i]),
                "p50": float(self.quantiles[1, i]),
                "p84": float(self.quantiles[2, i]),
                "sd_over_laplace": float(self.sd[i] / self.laplace_sd[i]),
                "shift_over_laplace": float((self.mean[i] - self.optimum[i]) / self.laplace_sd[i]),
                "autocorrelation": float(self.autocorrelation[i]),
            }
            for i, k in enumerate(self.keys)
        ]


def _calibration_json(calibration) -> Dict[str, Any]:
    if isinstance(calibration, CalibrationResult):
        path = calibration.out / "calibration.json"
    else:
        path = Path(calibration)
        if path.is_dir():
            path = path / "calibration.json"
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise _native.SceneError(f"calibration: cannot read {path}: {e}") from None


def _positive(name: str, value, minimum: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise _native.SceneError(f"{name}: an integer >= {minimum} is needed, found {value!r}")
    return int(value)


def posterior(
    file,
    calibration,
    set=None,
    walkers: Optional[int] = None,
    steps: int = 1000,
    burn: Optional[int] = None,
    thin: int = 1,
    seed: int = 1,
    threads: int = 2,
    scale: bool = False,
    out=None,
) -> PosteriorResult:
    """Sample the posterior of the constants of calibrate file ``file`` about the optimum
    of ``calibration`` (a :class:`CalibrationResult`, its folder or its calibration.json).

    Args:
        file: the calibrate file that made ``calibration``.
        calibration: what :func:`saltus.calibrate` (or ``saltus calibrate``) wrote.
        set: overrides of every run, as :func:`saltus.calibrate`'s (the calibration's own).
        walkers: ensemble size (default four per constant, at least 8; even).
        steps: steps of each walker.
        burn: steps dropped at the start (default a quarter of ``steps``).
        thin: keep every ``thin``-th step after the burn-in.
        seed: the seed of the walkers' start and of the sampler's moves.
        threads: model runs at once.
        scale: sample exp(-chi^2 / (2 s^2)), s the calibration's ``error_scale``, the
            counterpart of the scaled ``stderr``; else the counterpart of
            ``stderr_statistical``.
        out: a folder for ``posterior.csv`` (the draws) and ``posterior.json`` (the table).

    Raises:
        SceneError: the file or the calibration is refused, or they do not match.
        ImportError: emcee is not installed (``pip install emcee``).
    """
    try:
        import emcee
    except ImportError:
        raise ImportError("saltus.posterior samples with emcee: pip install emcee") from None
    j = _calibration_json(calibration)
    misfit = _native.Misfit(fspath(file, "file"), set)
    keys = misfit.keys
    got = [p["key"] for p in j["parameters"]]
    if got != keys:
        raise _native.SceneError(f"calibration: its constants {got} are not the file's {keys}")
    m = len(keys)
    walkers = max(8, 4 * m) if walkers is None else _positive("walkers", walkers, 2 * m)
    walkers += walkers % 2
    steps = _positive("steps", steps, 2)
    burn = steps // 4 if burn is None else _positive("burn", burn, 0)
    if burn >= steps:
        raise _native.SceneError(f"burn: {burn} leaves nothing of {steps} steps")
    thin = _positive("thin", thin)
    threads = _positive("threads", threads)
    seed = _positive("seed", seed, 0)

    optimum = np.array([p["value"] for p in j["parameters"]], dtype=float)
    statistical = np.array([np.nan if p["stderr_statistical"] is None else p["stderr_statistical"] for p in j["parameters"]])
    # the report writes null for a figure it has not (no finite chi^2 / dof): no scaling
    s = float(j["misfit"].get("error_scale") or 1.0) if scale else 1.0
    corr = np.array([[np.nan if v is None else v for v in row] for row in j["correlation"]], dtype=float)
    laplace_sd = statistical * s
    bounds = np.array(misfit.bounds, dtype=float)
    temperature = s * s

    misfit.anchor(list(optimum))

    def log_prob(p):
        c = misfit.chi2([float(v) for v in p])
        return -0.5 * c / temperature if math.isfinite(c) else -math.inf

    # the walkers start in a small ball about the optimum, inside the bounds
    rng = np.random.default_rng(seed)
    width = np.where(np.isfinite(laplace_sd) & (laplace_sd > 0), laplace_sd, 1e-3 * (bounds[:, 1] - bounds[:, 0]))
    inner_lo = bounds[:, 0] + 1e-6 * (bounds[:, 1] - bounds[:, 0])
    inner_hi = bounds[:, 1] - 1e-6 * (bounds[:, 1] - bounds[:, 0])
    start = np.clip(optimum + 0.1 * width * rng.standard_normal((walkers, m)), inner_lo, inner_hi)

    started = time.perf_counter()
    with ThreadPoolExecutor(max_workers=threads) as pool:
        sampler = emcee.EnsembleSampler(walkers, m, log_prob, pool=pool)
        sampler.random_state = np.random.RandomState(seed).get_state()
        sampler.run_mcmc(start, steps, progress=False)
    wall = time.perf_counter() - started

    chain = sampler.get_chain(discard=burn, thin=thin, flat=True)
    try:
        tau = np.asarray(sampler.get_autocorr_time(discard=burn, quiet=True), dtype=float)
    except Exception:  # emcee raises where a chain is too short for any estimate
        tau = np.full(m, np.nan)
    sample_corr = np.corrcoef(chain, rowvar=False) if m > 1 else np.ones((1, 1))
    result = PosteriorResult(
        keys=keys,
        samples=chain,
        mean=chain.mean(axis=0),
        sd=chain.std(axis=0, ddof=1),
        quantiles=np.percentile(chain, [16, 50, 84], axis=0),
        correlation=np.atleast_2d(sample_corr),
        optimum=optimum,
        laplace_sd=laplace_sd,
        laplace_correlation=corr,
        autocorrelation=tau,
        acceptance=float(np.mean(sampler.acceptance_fraction)),
        walkers=walkers,
        steps=steps,
        burn=burn,
        thin=thin,
        runs=walkers * (steps + 1),
        wall_time_s=wall,
        scale=s,
    )
    if out is not None:
        result.files = _write(result, Path(out), file)
    return result


def _finite(v: float) -> Optional[float]:
    return float(v) if math.isfinite(v) else None


def _write(r: PosteriorResult, out: Path, file) -> List[Path]:
    out.mkdir(parents=True, exist_ok=True)
    draws = out / "posterior.csv"
    with open(draws, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(r.keys)
        w.writerows([[repr(float(v)) for v in row] for row in r.samples])
    summary = out / "posterior.json"
    rows = [{k: (_finite(v) if isinstance(v, float) else v) for k, v in row.items()} for row in r.table()]
    with open(summary, "w") as f:
        json.dump(
            {
                "calibration": str(file),
                "sampler": "emcee EnsembleSampler (Goodman & Weare 2010 stretch move)",
                "walkers": r.walkers,
                "steps": r.steps,
                "burn": r.burn,
                "thin": r.thin,
                "draws": int(r.samples.shape[0]),
                "acceptance": r.acceptance,
                "runs": r.runs,
                "wall_time_s": r.wall_time_s,
                "error_scale": r.scale,
                "constants": rows,
                "correlation": [[_finite(v) for v in row] for row in r.correlation],
                "laplace_correlation": [[_finite(v) for v in row] for row in r.laplace_correlation],
            },
            f,
            indent=2,
        )
    return [draws, summary]
