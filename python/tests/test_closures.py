"""saltus.Closure: the closure laws against their equations and limits, broadcasting,
seeds, identity with `saltus closure eval`, errors."""

import csv
import io

import numpy as np
import pytest

import saltus


def test_stokes_drag_is_24_over_re():
    re = np.logspace(-3, 3, 61)
    cd = saltus.Closure("drag", {"type": "stokes"}).evaluate(re_p=re)["cd"]
    np.testing.assert_allclose(cd, 24.0 / re, rtol=1e-15, atol=0)


def test_toml_text_and_dict_give_the_same_model():
    re = np.array([0.5, 5.0, 500.0])
    a = saltus.Closure("drag", {"type": "dallavalle", "cd_inf": 0.44}).evaluate(re_p=re)["cd"]
    b = saltus.Closure("drag", 'type = "dallavalle"\ncd_inf = 0.44').evaluate(re_p=re)["cd"]
    c = saltus.Closure("drag", '{type = "dallavalle", cd_inf = 0.44}').evaluate(re_p=re)["cd"]
    assert np.array_equal(a, b) and np.array_equal(a, c)
    # Dallavalle as Chassagne et al. 2023 write it: C_D = cd_inf + a / Re_p, a = 24.4 by default
    np.testing.assert_allclose(a, 0.44 + 24.4 / re, rtol=1e-14)


@pytest.mark.parametrize("name", [m["name"] for m in saltus.models("hindrance")])
def test_every_hindrance_tends_to_one_in_the_dilute_limit(name):
    h = saltus.Closure("hindrance", {"type": name})
    re = np.array([0.1, 10.0, 1000.0])
    f = h.evaluate(phi=1e-12, re_p=re)["factor"]
    np.testing.assert_allclose(f, 1.0, rtol=0, atol=1e-10)
    # and hinders more (f grows) as phi grows, for a hindered model
    dense = h.evaluate(phi=0.4, re_p=re)["factor"]
    assert np.all(dense >= f)


def test_richardson_zaki_and_einstein_follow_their_equations():
    phi = np.linspace(0.0, 0.6, 13)
    f = saltus.Closure("hindrance", {"type": "richardson_zaki", "exponent": 4.65}).evaluate(phi=phi, re_p=1.0)
    np.testing.assert_allclose(f["factor"], (1 - phi) ** -4.65, rtol=1e-13)
    nu = saltus.Closure("viscosity", {"type": "einstein"}).evaluate(phi=phi)["nu_ratio"]
    np.testing.assert_allclose(nu, 1 + 2.5 * phi, rtol=1e-15)


def test_mu_i_between_its_static_and_dynamic_friction():
    c = saltus.Closure("granular", {"type": "mu_i"})
    p = {q["name"]: q["value"] for q in c.params}
    out = c.evaluate(i=[0.0, p["i0"], 1e12])
    np.testing.assert_allclose(out["mu"], [p["mu_s"], 0.5 * (p["mu_s"] + p["mu_2"]), p["mu_2"]], rtol=1e-10)
    # phi = phi_c / (1 + b I)
    np.testing.assert_allclose(out["phi"][:2], p["phi_c"] / (1 + p["b"] * np.array([0.0, p["i0"]])), rtol=1e-14)


def test_kinetic_theory_radial_distribution_is_one_when_dilute():
    kt = saltus.Closure("kinetic_theory", {})  # type defaults to frictional_collisional
    assert kt.name == "frictional_collisional"
    out = kt.evaluate(phi=[1e-9, 0.3, 0.5])
    assert abs(out["g0"][0] - 1.0) < 1e-6
    assert np.all(np.diff(out["g0"]) > 0)  # contacts more frequent as grains crowd
    assert set(out) == {"g0", "f1", "f2", "f3", "f4", "e_eff"}


def test_scalars_broadcast_and_shapes_are_kept():
    h = saltus.Closure("hindrance", {"type": "richardson_zaki", "exponent": 2.0})
    phi = np.array([[0.0, 0.5], [0.25, 0.75]])
    f = h.evaluate(phi=phi, re_p=3.0)["factor"]
    assert f.shape == (2, 2) and f.dtype == np.float64
    np.testing.assert_allclose(f, (1 - phi) ** -2.0, rtol=1e-15)
    scalar = h.evaluate(phi=0.5, re_p=1.0)["factor"]
    assert scalar.shape == () and float(scalar) == 4.0


def test_turbulence_mixing_length_grows_as_kappa_z_in_clear_fluid():
    c = saltus.Closure("turbulence", {"type": "mixing_length", "kappa": 0.41})
    z = (np.arange(20) + 0.5) * 1e-3
    out = c.evaluate(z=z, phi=0.0, dudz=1.0, d=1e-3)
    # clear fluid, l = kappa z at the cell centres (integral of 1 from the wall); nu_t = l^2 |du/dz|
    np.testing.assert_allclose(out["l_m"], 0.41 * z, rtol=1e-12)
    np.testing.assert_allclose(out["nu_t"], out["l_m"] ** 2, rtol=1e-12)


def _fluctuation_inputs():
    n = 6
    return {
        "k": np.linspace(1e-4, 1e-2, n),
        "omega": np.linspace(1.0, 10.0, n),
        "nu_t": np.full(n, 1e-5),
        "reynolds_stress": np.linspace(0.1, 1.0, n),
        "slip": np.full(n, 0.05),
        "response_time": np.full(n, 0.01),
        "depth": np.full(n, 0.1),
        "bulk_velocity": np.full(n, 0.5),
    }


def test_fluctuation_draws_follow_the_seed():
    c = saltus.Closure("fluctuation", {"type": "eim"}, seed=3)
    x = _fluctuation_inputs()
    a, b = c.evaluate(**x), c.evaluate(**x)
    assert all(np.array_equal(a[k], b[k]) for k in a)  # reproducible
    other = c.evaluate(seed=4, **x)
    assert not np.array_equal(a["u_x"], other["u_x"])
    assert np.array_equal(a["diffusivity"], other["diffusivity"])  # not drawn
    assert np.array_equal(saltus.Closure("fluctuation", {"type": "eim"}, seed=4).evaluate(**x)["u_x"], other["u_x"])


@pytest.mark.parametrize(
    "family,model,inputs,seed",
    [
        ("drag", 'type = "haider_levenspiel"', {"re_p": [0.1, 1.0, 10.0, 100.0, 1000.0]}, 0),
        ("kinetic_theory", "restitution = 0.7", {"phi": [0.01, 0.3, 0.55]}, 0),
        ("fluctuation", 'type = "eim"', _fluctuation_inputs(), 11),
    ],
)
def test_closure_eval_from_python_is_the_command_lines(cli, tmp_path, family, model, inputs, seed):
    names = list(inputs)
    rows = zip(*(np.asarray(inputs[k], dtype=float) for k in names))
    path = tmp_path / "in.csv"
    path.write_text(",".join(names) + "\n" + "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows))
    code, out, err = cli(
        "closure", "eval", "--family", family, "--model", model, "--input", str(path), "--seed", str(seed)
    )
    assert code == 0, err
    table = list(csv.DictReader(io.StringIO(out)))
    got = saltus.Closure(family, model, seed=seed).evaluate(**inputs)
    for name, values in got.items():
        # identity: the same code; the CLI writes shortest round-trip decimals
        assert np.array_equal(values, [float(r[name]) for r in table]), name


def test_params_and_describe_match_the_model_listing():
    c = saltus.Closure("hindrance", {"type": "richardson_zaki", "exponent": 4.0})
    listed = next(m for m in saltus.models("hindrance") if m["name"] == "richardson_zaki")
    d = c.describe()
    assert (d["name"], d["equation"], d["source"]) == (listed["name"], listed["equation"], listed["source"])
    (p,) = c.params
    (q,) = listed["parameters"]
    assert p["value"] == 4.0 and p["default"] == q["default"]
    assert {k: p[k] for k in ("name", "range", "unit", "doc")} == {k: q[k] for k in ("name", "range", "unit", "doc")}


def test_bad_closures_and_inputs_are_refused_with_their_key():
    with pytest.raises(saltus.SceneError) as e:
        saltus.Closure("drag", {"type": "stoke"})
    assert "unknown drag model `stoke`" in str(e.value) and "stokes" in str(e.value)
    assert e.value.key == "drag.type" and e.value.file == "saltus.Closure"
    with pytest.raises(saltus.SceneError, match=r"hindrance.exponent` = -1: out of range"):
        saltus.Closure("hindrance", {"type": "richardson_zaki", "exponent": -1.0})
    with pytest.raises(saltus.SceneError, match="TOML syntax error"):
        saltus.Closure("drag", "type = = 1")
    with pytest.raises(saltus.SceneError, match="not a local rheology"):
        saltus.Closure("granular", {"type": "frictional_collisional"})
    with pytest.raises(ValueError, match="unknown family `dragg`; known: drag, hindrance"):
        saltus.Closure("dragg", {"type": "stokes"})
    stokes = saltus.Closure("drag", {"type": "stokes"})
    with pytest.raises(TypeError, match="unknown input 'rep'"):
        stokes.evaluate(rep=1.0)
    with pytest.raises(ValueError, match="missing input column `re_p`"):
        stokes.evaluate()
    with pytest.raises(ValueError, match=r"row 1: re_p = -1: allowed finite values >= 0"):
        stokes.evaluate(re_p=[1.0, -1.0])
    with pytest.raises(ValueError, match=r"row 2: phi = 1.5 outside \[0, 1\)"):
        saltus.Closure("viscosity", {"type": "einstein"}).evaluate(phi=[0.1, 0.2, 1.5])
    with pytest.raises(ValueError, match="not a finite number"):
        saltus.Closure("viscosity", {"type": "einstein"}).evaluate(phi=[np.nan])
