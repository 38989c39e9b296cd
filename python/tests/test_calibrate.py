"""saltus.calibrate: closure constants recovered from a reference the model made itself,
and a bad calibrate file refused by key, as the command line refuses it."""

import math
from pathlib import Path

import pytest

import saltus

ROOT = Path(__file__).resolve().parents[2]
CASE01 = ROOT / "cases" / "chassagne2023" / "case01.toml"


def _calibrate_file(tmp_path, reference, parameters):
    p = tmp_path / "cal.toml"
    p.write_text(
        f"base = '{CASE01}'\n{parameters}\n[reference]\nruns = ['{reference}']\n"
        "scatter = { phi = 0.01, u_p = 0.01 }\n[optimiser]\nprofile_points = 1\n"
    )
    return p


def test_the_elastic_modulus_of_a_synthetic_reference_is_recovered(tmp_path):
    # case 1 run with P0 = 0.08 Pa (eq 2.14; default 0.05): the calibration from the
    # default finds 0.08 far inside its error bar and removes the misfit
    ref = tmp_path / "ref"
    made = saltus.run(CASE01, set={"closures.granular.p0": 0.08}, out=ref)
    cal = _calibrate_file(tmp_path, ref, "[[parameter]]\nkey = 'closures.granular.p0'\nbounds = [0.01, 0.5]\n")
    assert "1 free constants" in saltus.check_calibration(cal)
    r = saltus.calibrate(cal, out=tmp_path / "out")
    p = r.parameters[0]
    assert p["key"] == "closures.granular.p0"
    assert abs(p["value"] - 0.08) < 1e-3 * 0.08, p
    assert math.isfinite(p["stderr"]) and abs(p["value"] - 0.08) < 0.05 * p["stderr"]
    assert r.values == {"closures.granular.p0": p["value"]}
    assert r.chi2_start > 0.1 and r.chi2 < 1e-4 * r.chi2_start
    assert r.correlation.shape == (1, 1) and r.correlation[0, 0] == pytest.approx(1.0)
    assert len(r.evaluations["chi2"]) > 5 and set(r.evaluations["purpose"]) >= {"minimise"}
    assert r.calibrated.is_file() and r.optimiser["converged"]
    # the calibrated closures run back through saltus.run
    again = saltus.run(CASE01, closures=r.calibrated, out=tmp_path / "again")
    assert again.summary["qs_star"] == pytest.approx(made.summary["qs_star"], rel=1e-4)


def test_a_start_outside_the_bounds_is_refused_by_key(tmp_path):
    ref = ROOT / "cases" / "chassagne2023" / "reference" / "case01_dem_s1"
    cal = _calibrate_file(tmp_path, ref, "[[parameter]]\nkey = 'closures.granular.p0'\nbounds = [0.1, 0.5]\nstart = 0.05\n")
    for call in (lambda: saltus.check_calibration(cal), lambda: saltus.calibrate(cal, out=tmp_path / "out")):
        with pytest.raises(saltus.SceneError, match="closures.granular.p0"):
            call()
    assert not (tmp_path / "out" / "calibration.json").exists()
