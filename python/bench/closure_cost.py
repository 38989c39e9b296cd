"""Run-time cost of closures written in Python (docs/python.md, "Cost"): wall time of case 1
with the built-in Dallavalle + Richardson-Zaki and with their numpy re-implementation of
python/tests/test_python_closures.py, the best of N runs, the qs* of both and the number
of Python calls.

    python python/bench/closure_cost.py eulerian,eulerian_2000s,small_dem 3
    python python/bench/closure_cost.py full_dem 1

Run from the repository root with the package installed."""
import sys, time
import numpy as np
import saltus

calls = {"drag": [0, 0], "hindrance": [0, 0]}

def dallavalle(re_p, cd_inf, a):
    calls["drag"][0] += 1; calls["drag"][1] += re_p.size
    with np.errstate(divide="ignore"):
        return {"cd": cd_inf + a / re_p, "cd_re": cd_inf * re_p + a}

def rz(phi, re_p, exponent):
    calls["hindrance"][0] += 1; calls["hindrance"][1] += phi.size
    return (1.0 - phi) ** (-exponent)

saltus.register_closure("drag", "py_dallavalle", dallavalle, params={"cd_inf": 0.4, "a": 24.4})
saltus.register_closure("hindrance", "py_richardson_zaki", rz, params={"exponent": 3.1}, depends_on_reynolds=False)
PY = {"closures.drag.type": "py_dallavalle", "closures.hindrance.type": "py_richardson_zaki"}
SMALL_DEM = {"solver.type": "lagrangian", "solver.lagrangian.length": 0.036, "solver.lagrangian.width": 0.036,
             "domain.bed_height": 0.018, "domain.water_depth": 0.03, "solver.lagrangian.settle_time": 0.1,
             "solver.lagrangian.end_time": 0.1, "solver.lagrangian.stats_start": 0.0}
FULL_DEM = {"solver.type": "lagrangian", "solver.lagrangian.settle_time": 0.1,
            "solver.lagrangian.end_time": 0.1, "solver.lagrangian.stats_start": 0.0}
cases = {"eulerian": {}, "eulerian_2000s": {"solver.eulerian.steady_tolerance": 0.0},
         "small_dem": SMALL_DEM, "full_dem": FULL_DEM}
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
for name in sys.argv[1].split(","):
    base = cases[name]
    out = {}
    for label, laws in [("built-in", {}), ("python", PY)]:
        best = None
        for _ in range(repeats):
            for c in calls.values(): c[:] = [0, 0]
            t = time.perf_counter()
            r = saltus.run("cases/chassagne2023/case01.toml", set={**base, **laws}, out=False)
            w = time.perf_counter() - t
            best = w if best is None else min(best, w)
        out[label] = (best, r.summary["qs_star"], r.summary.get("steps"), dict(calls))
    b, p = out["built-in"], out["python"]
    print(f"{name}: built-in {b[0]:.3f} s, python {p[0]:.3f} s, ratio {p[0]/b[0]:.2f}; qs* {b[1]!r} vs {p[1]!r} "
          f"(equal: {b[1] == p[1]}); steps {b[2]}; python calls (n, rows) {p[3]}", flush=True)
