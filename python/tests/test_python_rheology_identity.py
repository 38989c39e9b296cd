"""A numpy mu(I) with the arithmetic of the built-in `mu_i` (closures/src/granular/mu_i.rs),
law and closed-form inverse, runs the dry incline in the Eulerian solver and two sheet
flows (Revil-Baudard et al. 2015 with mu(I), Chassagne et al. 2023 case 1 with
`closures.granular = mu_i`) bit for bit as the built-in law: every summary figure of the
run and every profile equal."""

import numpy as np
import pytest

import saltus

MU_I = {"mu_s": 0.35, "mu_2": 0.97, "i0": 0.69, "phi_c": 0.61, "b": 0.31}


# The law and its inverse use only +, -, *, / and max, which IEEE 754 rounds exactly in
# numpy's vectorised loops as in Rust: written in the Rust code's operation order, numpy
# gives the built-in values bit for bit (a law with pow, tanh or atan would need Python's
# `math` per element for that, as test_python_kinetic.py does).
def mu_i(i, mu_s, mu_2, i0, phi_c, b, **grain):
    """mu = mu_s + (mu_2 - mu_s) / (i0 / I + 1), phi = phi_c / (1 + b I)"""
    with np.errstate(divide="ignore"):
        # MuI::friction: mu_s at I <= 0; I = +inf gives i0 / I = 0, mu_2
        mu = np.where(i <= 0.0, mu_s, mu_s + (mu_2 - mu_s) / (i0 / i + 1.0))
    # MuI::packing: phi_c / (1 + b max(I, 0)); np.fmax is Rust's f64::max (NaN gives 0)
    return {"mu": mu, "phi": phi_c / (1.0 + b * np.fmax(i, 0.0))}


def mu_i_inverse(phi, mu_s, mu_2, i0, phi_c, b, **grain):
    """I = (phi_c / phi - 1) / b"""
    # MuI::control_of_packing, its branches in its order: 0 at phi >= phi_c, +inf at
    # phi <= 0, b = 0 or NaN, else the closed form
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        x = (phi_c / phi - 1.0) / b
    dilute = (phi <= 0.0) | (b == 0.0) | np.isnan(phi)
    return np.where(phi >= phi_c, 0.0, np.where(dilute, np.inf, x))


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
