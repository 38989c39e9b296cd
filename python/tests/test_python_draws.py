"""The particle face of a fluctuation closure written in Python in the DEM: one call per
chunk of particles (arrays in, arrays out), each draw's variates from its own particle's
seeded stream, so that a run is the same bit for bit on one thread and on two, and the
same as the built-in eddy interaction model drawing once per particle."""

import math

import numpy as np
import pytest

import saltus
from laws import eim_diffusivity

SHEET_FLOW = "cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml"
# 5 d x 5 d of the sheet flow (about 210 grains), the first 0.3 s
SHORT = {"solver.lagrangian.length": 0.015, "solver.lagrangian.width": 0.015,
         "solver.lagrangian.end_time": 0.3, "solver.lagrangian.stats_start": 0.0}
VARIATES = {"n_x": "normal", "n_y": "normal", "n_z": "normal", "e": "exponential"}

calls = []


def eim_draw(k, omega, nu_t, reynolds_stress, slip, response_time, n_x, n_y, n_z, e, c0, c_mu, depth, bulk_velocity):
    """u = sqrt(2k/3) n, duration = min(C0 T_L e, t_c) (Cheng et al. eqs 36-37)"""
    # the built-in eim's arithmetic per draw, with the C library's sqrt and log1p
    calls.append(len(k))
    n = len(k)
    u = np.zeros((3, n))
    duration = np.full(n, np.inf)
    for j in range(n):
        w = float(omega[j])
        den = 6.0 * c_mu * w
        if not (math.isfinite(w) and w > 0.0 and den > 0.0 and math.isfinite(1.0 / den)):
            continue
        t_e = c0 * (1.0 / den) * e[j]
        kj = float(k[j])
        if not (math.isfinite(kj) and kj > 0.0):
            duration[j] = t_e
            continue
        s = math.sqrt(2.0 * kj / 3.0)
        l_e = t_e * s
        d = t_e
        sl, tp = float(slip[j]), float(response_time[j])
        if math.isfinite(sl) and sl > 0.0 and tp > 0.0 and math.isfinite(l_e):
            if math.isinf(tp):
                d = min(l_e / sl, t_e)
            elif l_e < sl * tp:
                d = min(-tp * math.log1p(-l_e / (sl * tp)), t_e)
        u[:, j] = s * n_x[j], s * n_y[j], s * n_z[j]
        duration[j] = d
    return {"u_x": u[0], "u_y": u[1], "u_z": u[2], "duration": duration}


@pytest.fixture(scope="module", autouse=True)
def python_eim():
    saltus.register_fluctuation("py_eim_chunked", eim_draw, eim_diffusivity, params={"c0": 3.0, "c_mu": 0.09},
                                variates=VARIATES, needs=["k", "omega"])
    yield
    saltus.unregister_closure("fluctuation", "py_eim_chunked")


def run(root, fluctuation, threads):
    overrides = {**SHORT, "solver.lagrangian.threads": threads, "closures.fluctuation": fluctuation}
    return saltus.run(root / SHEET_FLOW, set=overrides, out=False)


def test_python_draws_are_one_call_per_chunk_and_the_same_on_one_and_two_threads(root):
    calls.clear()
    one = run(root, {"type": "py_eim_chunked"}, 1)
    per_call = list(calls)
    calls.clear()
    two = run(root, {"type": "py_eim_chunked"}, 2)
    built_in = run(root, {"type": "eim", "c0": 3.0}, 2)
    assert one.ending == "end_time" and one.summary["particles"] > 100, one.summary
    # one call per chunk of 256 particles with draws due, not per particle
    assert sum(per_call) > 10 * len(per_call) and max(per_call) <= 256, (len(per_call), sum(per_call))
    assert sorted(calls) == sorted(per_call)
    for other in (two, built_in):
        assert other.summary["qs_star"] == one.summary["qs_star"]
        for name, values in one.profiles.items():
            np.testing.assert_array_equal(other.profiles[name], values, err_msg=name)
