"""A numpy mu(I) with the arithmetic of the built-in `mu_i` (closures/src/granular/mu_i.rs),
law and closed-form inverse, runs the dry incline in the Eulerian solver and two sheet
flows (Revil-Baudard et al. 2015 with mu(I), Chassagne et al. 2023 case 1 with
`closures.granular = mu_i`) bit for bit as the built-in law: every summary figure of the
run and every profile equal."""

import numpy as np
import pytest

import saltus

from laws import MU_I, mu_i, mu_i_inverse

# (scene, overrides): the dry incline is a DEM scene, run here in the Eulerian solver with the
# settings of its compare file (cases/granular/compare_dry_incline_fit.toml: air, the DEM's
# packing and bed, 100 cells) to its end time; the sheet flows run to steady (581 and 835
# steps)
SCENES = {
    "dry_incline": (
        "cases/granular/dry_incline.toml",
        {
            "solver.type": "eulerian",
            "fluid.density": 1.2,
            "fluid.viscosity": 1.5e-5,
            "domain.bed_phi": 0.55,
            "domain.bed_height": 0.07854545454545454,
            "domain.cells": 100,
        },
    ),
    "revil_baudard_sheet_flow": ("cases/revil_baudard2015/sheet_flow_mu_i.toml", {}),
    "chassagne_case01": ("cases/chassagne2023/case01.toml", {}),
}

# the run's clocks differ between any two runs
CLOCKS = {"wall_time_s", "cpu_time_s", "timing"}


@pytest.fixture(scope="module", autouse=True)
def python_mu_i():
    saltus.register_rheology("py_mu_i_exact", mu_i, params=MU_I, inverse=mu_i_inverse)
    yield
    saltus.unregister_closure("granular", "py_mu_i_exact")


@pytest.mark.parametrize("scene", list(SCENES))
def test_numpy_mu_i_runs_the_scene_bit_for_bit(root, scene):
    path, overrides = SCENES[scene]
    built_in = saltus.run(root / path, set={**overrides, "closures.granular": {"type": "mu_i"}}, out=False)
    python = saltus.run(root / path, set={**overrides, "closures.granular": {"type": "py_mu_i_exact"}}, out=False)
    assert built_in.summary["qs_star"] > 0.1, built_in.summary
    for key, value in built_in.summary.items():
        if key not in CLOCKS:
            assert python.summary[key] == value, (key, python.summary[key], value)
    assert set(python.profiles) == set(built_in.profiles)
    for name, values in built_in.profiles.items():
        # NaN where a profile has no value (no grains): at the same cells in both
        np.testing.assert_array_equal(python.profiles[name], values, err_msg=name)


def test_the_numpy_law_gives_the_built_in_values():
    built_in = saltus.Closure("granular", {"type": "mu_i"})
    python = saltus.Closure("granular", {"type": "py_mu_i_exact"})
    # Closure.evaluate takes finite inputs only: 1e300 stands for I -> inf
    i = np.concatenate(([0.0, 1e-300, 1e-12, 0.69, 1e300], np.geomspace(1e-8, 1e4, 997)))
    a, b = built_in.evaluate(i=i), python.evaluate(i=i)
    np.testing.assert_array_equal(b["mu"], a["mu"])
    np.testing.assert_array_equal(b["phi"], a["phi"])
