"""Run-time cost of the granular, turbulence and fluctuation faces written in Python
(docs/python.md, "Cost of the faces"): wall time of a run with the built-in model and with
its numpy re-implementation of python/tests (test_python_faces.py, test_python_kinetic.py),
the best of N runs, the qs* of both and the Python calls (count, rows) per run.

    python python/bench/face_cost.py rheology,kinetic,mixing_length 3
    python python/bench/face_cost.py fluctuation 1

Run from the repository root with the package installed. rheology, kinetic and
mixing_length run Chassagne case 1 (Eulerian, to steady); fluctuation runs the first 1 s
of the DEM of the Revil-Baudard sheet flow with k-omega and the eddy interaction model
(cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml, 840 grains, 10 d x 10 d)."""
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import saltus  # noqa: E402
import test_python_faces as faces  # noqa: E402
import test_python_kinetic as kinetic  # noqa: E402

calls = {}


def counted(name, f):
    def wrapped(**kw):
        c = calls.setdefault(name, [0, 0])
        c[0] += 1
        c[1] += len(next(iter(kw.values())))
        return f(**kw)

    wrapped.__doc__ = f.__doc__
    return wrapped


saltus.register_rheology("py_mu_i", counted("rheology", faces.mu_i), params=faces.MU_I,
                         inverse=counted("inverse", faces.mu_i_inverse))
saltus.register_kinetic_theory("py_proposed", counted("kinetic", kinetic.proposed), params=kinetic.PROPOSED,
                               saltation=True)
saltus.register_mixing_length("py_li_sawamoto", counted("mixing_length", faces.li_sawamoto),
                              params={"kappa": 0.41, "phi_max": 0.635})
saltus.register_fluctuation("py_eim", counted("draw", faces.eim_draw), counted("diffusivity", faces.eim_diffusivity),
                            params={"c0": 3.0, "c_mu": 0.09},
                            variates={"n_x": "normal", "n_y": "normal", "n_z": "normal", "e": "exponential"},
                            needs=["k", "omega"])

CASE01 = "cases/chassagne2023/case01.toml"
SHEET_FLOW = "cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml"
DEM_1S = {"solver.lagrangian.end_time": 1.0, "solver.lagrangian.stats_start": 0.0}
CASES = {
    # (scene, overrides of both runs, the built-in table, the Python table)
    "rheology": (CASE01, {}, {"closures.granular": {"type": "mu_i"}}, {"closures.granular": {"type": "py_mu_i"}}),
    "kinetic": (CASE01, {}, {}, {"closures.granular": {"type": "py_proposed"}}),
    "mixing_length": (CASE01, {}, {}, {"closures.turbulence": {"type": "py_li_sawamoto", "phi_max": 0.6125}}),
    "fluctuation": (SHEET_FLOW, DEM_1S, {"closures.fluctuation": {"type": "eim", "c0": 3.0}},
                    {"closures.fluctuation": {"type": "py_eim", "c0": 3.0}}),
}

repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
for name in sys.argv[1].split(","):
    scene, base, built_in, python = CASES[name]
    out = {}
    for label, laws in [("built-in", built_in), ("python", python)]:
        best = None
        for _ in range(repeats):
            calls.clear()
            t = time.perf_counter()
            r = saltus.run(scene, set={**base, **laws}, out=False)
            w = time.perf_counter() - t
            best = w if best is None else min(best, w)
        out[label] = (best, r.summary.get("qs_star"), r.summary.get("steps"), {k: tuple(v) for k, v in calls.items()})
    b, p = out["built-in"], out["python"]
    rel = abs(p[1] - b[1]) / abs(b[1]) if b[1] else float("nan")
    print(f"{name}: built-in {b[0]:.3f} s, python {p[0]:.3f} s, ratio {p[0] / b[0]:.2f}; qs* {b[1]!r} vs {p[1]!r} "
          f"(relative difference {rel:.1e}); steps {b[2]} / {p[2]}; python calls (n, rows) {p[3]}", flush=True)
