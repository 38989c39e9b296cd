"""saltus.posterior: an MCMC sample of a calibration's constants agrees with the Laplace
approximation where chi^2 is near-quadratic, is reproducible for a seed at any thread
count, and refuses bad input by name."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import saltus


ROOT = Path(__file__).resolve().parents[2]
FRY = ROOT / "cases" / "fry2024"


def _one_constant(tmp_path):
    # Fry et al. 2024's Couette bedload, the viscosity exponent beta (eq 51) alone, on the
    # two DEM seeds: runs of 8 ms, chi^2 near-quadratic in beta about its optimum
    p = tmp_path / "beta.toml"
    p.write_text(
        f"base = '{FRY / 'couette_bedload.toml'}'\n"
        "set = ['closures.viscosity={type=\"fry2024\", beta0=1.7635, a=0.0}']\n"
        "[[parameter]]\nkey = 'closures.viscosity.beta0'\nbounds = [0.5, 4.0]\n"
        f"[reference]\nruns = ['{FRY / 'reference' / 'couette_dem_s1'}', '{FRY / 'reference' / 'couette_dem_s2'}']\n"
        "smooth = 1.0\nalign = true\n[misfit]\nterms = ['phi', 'u_p', 'qs_star']\n"
        "[optimiser]\nprofile_points = 1\n"
    )
    return p


def test_the_sample_agrees_with_quadrature_and_the_laplace_errors_and_is_reproducible(tmp_path):
    cal = _one_constant(tmp_path)
    c = saltus.calibrate(cal, out=tmp_path / "cal")
    optimum, sd0 = c.parameters[0]["value"], c.parameters[0]["stderr_statistical"]
    # the exact posterior of one constant by quadrature of exp(-chi^2 / 2) over +-5 sd
    m = saltus._native.Misfit(str(cal))
    m.anchor([optimum])
    x = optimum + sd0 * np.linspace(-5.0, 5.0, 81)
    chi2 = np.array([m.chi2([v]) for v in x])
    w = np.exp(-0.5 * (chi2 - chi2.min()))
    mean = np.trapezoid(w * x, x) / np.trapezoid(w, x)
    sd = math.sqrt(np.trapezoid(w * (x - mean) ** 2, x) / np.trapezoid(w, x))
    # near-quadratic: the Laplace approximation within 15 % in sd, 0.3 sd in the mean
    assert abs(sd / sd0 - 1.0) < 0.15 and abs(mean - optimum) < 0.3 * sd0, (mean, sd, optimum, sd0)
    r = saltus.posterior(cal, c, walkers=12, steps=250, burn=60, seed=3, out=tmp_path / "post")
    assert r.laplace_sd[0] == pytest.approx(sd0)
    # 2280 correlated draws (tau ~ 10-20 steps): the quadrature's sd to 20 %, its mean to
    # 0.3 sd
    assert abs(r.sd[0] / sd - 1.0) < 0.2, (r.sd, sd)
    assert abs(r.mean[0] - mean) < 0.3 * sd, (r.mean, mean, sd)
    assert 0.2 < r.acceptance < 0.95
    assert r.samples.shape == (12 * 190, 1) and r.runs == 12 * 251
    lo, hi = c.parameters[0]["bounds"]
    assert np.all((r.samples > lo) & (r.samples < hi))
    summary = json.loads((tmp_path / "post" / "posterior.json").read_text())
    assert summary["draws"] == 2280 and summary["constants"][0]["key"] == "closures.viscosity.beta0"
    rows = (tmp_path / "post" / "posterior.csv").read_text().splitlines()
    assert len(rows) == 2281 and all(math.isfinite(float(v)) for v in rows[1:])
    # the same draws on one thread as on two
    a = saltus.posterior(cal, c, walkers=8, steps=6, burn=0, seed=5, threads=1)
    b = saltus.posterior(cal, c, walkers=8, steps=6, burn=0, seed=5, threads=2)
    assert np.array_equal(a.samples, b.samples)


def test_bad_input_is_refused_by_name(tmp_path):
    cal = _one_constant(tmp_path)
    c = saltus.calibrate(cal, out=tmp_path / "cal")
    for kwargs, name in [
        ({"walkers": 0}, "walkers"),
        ({"walkers": 2.5}, "walkers"),
        ({"steps": 0}, "steps"),
        ({"steps": 4, "burn": 4}, "burn"),
        ({"threads": 0}, "threads"),
        ({"seed": -1}, "seed"),
        ({"seed": "one"}, "seed"),
    ]:
        with pytest.raises(saltus.SceneError, match=name):
            saltus.posterior(cal, c, **kwargs)
    with pytest.raises(saltus.SceneError, match="calibration"):
        saltus.posterior(cal, tmp_path / "nowhere")
    other = FRY / "calibrate_couette.toml"
    with pytest.raises(saltus.SceneError, match="not the file's"):
        saltus.posterior(other, c)
    m = saltus._native.Misfit(str(cal))
    with pytest.raises(ValueError, match="not finite"):
        m.chi2([math.nan])
    with pytest.raises(ValueError, match="1 free constants"):
        m.chi2([1.0, 2.0])
    assert m.chi2([10.0]) == math.inf  # outside the bounds
