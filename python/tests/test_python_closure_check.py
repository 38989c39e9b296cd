"""saltus.closure_check on the granular, turbulence and fluctuation faces written in
Python: the limits a registration declares (mu -> mu_s as I -> 0, packing decreasing in I,
g0 -> 1 as phi -> 0, l_m ~ kappa z at the wall, D >= 0) pass for the numpy versions of the
built-in laws and fail, with the shrunk input, for laws broken on purpose."""

import numpy as np
import pytest

import saltus


def documented(default, range_, unit, description):
    return {"default": default, "range": range_, "unit": unit, "description": description}


MU_I = {
    "mu_s": documented(0.35, "[0, 0.9]", "-", "quasi-static friction"),
    "mu_2": documented(0.97, "[0.9, 3]", "-", "friction at large I"),
    "i0": documented(0.69, "(0, 10]", "-", "inertial number scale"),
    "phi_c": documented(0.61, "(0, 1)", "-", "packing at I = 0"),
    "b": documented(0.31, "[0, 10]", "-", "dilatancy coefficient"),
}
RHEOLOGY_LIMITS = [("static_friction", "mu_s"), "packing_decreasing", "increasing"]


def mu_i(i, mu_s, mu_2, i0, phi_c, b, **grain):
    """mu = mu_s + (mu_2 - mu_s) / (i0 / I + 1), phi = phi_c / (1 + b I)"""
    with np.errstate(divide="ignore"):
        mu = np.where(i <= 0.0, mu_s, mu_s + (mu_2 - mu_s) / (i0 / i + 1.0))
    return {"mu": mu, "phi": phi_c / (1.0 + b * np.maximum(i, 0.0))}


def mu_i_offset(i, mu_s, mu_2, i0, phi_c, b, **grain):
    """mu(I) 0.05 above mu_s as soon as I > 0"""
    out = mu_i(i, mu_s, mu_2, i0, phi_c, b)
    out["mu"] = out["mu"] + np.where(i > 0.0, 0.05, 0.0)
    return out


def mu_i_compacting(i, mu_s, mu_2, i0, phi_c, b, **grain):
    """phi grows again above I = 0.5"""
    out = mu_i(i, mu_s, mu_2, i0, phi_c, b)
    out["phi"] = out["phi"] + 0.5 * np.maximum(i - 0.5, 0.0)
    return out


KINETIC = {"a": documented(0.58, "[0, 100]", "-", "coefficient of the divergent term of g0 (eq 2.23)")}


def chialvo_sundaresan(phi, a, p0, phi_rlp, phi_max, static_friction, diameter, density, restitution, friction,
                       g0_offset=0.0, **salt):
    """g0 of Chialvo & Sundaresan (eq 2.23), F1-F4 of Garzo & Dufty (table 1, left column)"""
    e = restitution
    with np.errstate(divide="ignore", invalid="ignore"):
        g0 = (2.0 - phi) / (2.0 * (1.0 - phi) ** 3) + a * phi**2 / (phi_max - phi) ** 1.5 + g0_offset
    g0 = np.where(phi >= phi_max, np.inf, g0)
    sqrt_pi = np.sqrt(np.pi)
    eta_k = 5.0 * sqrt_pi / 96.0 * (1.0 / g0 - 0.4 * (1 + e) * (1 - 3 * e) * phi) / (
        1.0 - 0.25 * (1 - e) ** 2 - 5.0 / 24.0 * (1 - e * e))
    kappa_k = 225.0 * sqrt_pi / 576.0 * (1.0 / g0 + 0.6 * (1 + e) ** 2 * (2 * e - 1) * phi) / (
        (1.0 - 7.0 / 16.0 * (1 - e)) * (1 + e))
    return {
        "g0": g0,
        "f1": phi * (1.0 + 2.0 * (1.0 + e) * phi * g0),
        "f2": eta_k * (1.0 + 0.8 * (1 + e) * phi * g0) + 0.8 / sqrt_pi * (1 + e) * phi**2 * g0,
        "f3": kappa_k * (1.0 + 1.2 * (1 + e) * phi * g0) + 2.0 / sqrt_pi * (1 + e) * phi**2 * g0,
        "f4": 12.0 / sqrt_pi * (1.0 - e * e) * phi**2 * g0,
        "e_eff": np.full_like(phi, e),
    }


def g0_offset(phi, **kw):
    """g0 0.1 above Carnahan-Starling at phi = 0"""
    return chialvo_sundaresan(phi, g0_offset=0.1, **kw)


LENGTH = {
    "kappa": documented(0.41, "(0, 1]", "-", "von Karman constant"),
    "phi_max": documented(0.635, "(0, 1)", "-", "packing where l_m stops growing"),
}


def li_sawamoto(z, dz, phi, dudz, kappa, phi_max, diameter, nu_f):
    """l = kappa int_0^z (1 - phi/phi_max) dz' (Li & Sawamoto 1995, Chassagne et al. 2023 eq 2.8b)"""
    f = np.clip(1.0 - phi / phi_max, 0.0, 1.0)
    below = np.concatenate(([0.0], np.cumsum(f * dz)[:-1]))
    face = np.concatenate(([0.0], np.cumsum(dz)[:-1]))
    return kappa * (below + f * (z - face))


def rough_wall(z, dz, phi, dudz, kappa, phi_max, diameter, nu_f):
    """l = kappa (z + d): a roughness length the wall limit refuses"""
    return kappa * (z + diameter)


EIM = {
    "c0": documented(3.0, "(0, 10]", "-", "eddy lifetime over the Lagrangian time"),
    "c_mu": documented(0.09, "(0, 1]", "-", "k-omega constant of T_L = 1 / (6 C_mu omega)"),
}
VARIATES = {"n_x": "normal", "n_y": "normal", "n_z": "normal", "e": "exponential"}


def eim_draw(k, omega, nu_t, reynolds_stress, slip, response_time, n_x, n_y, n_z, e, c0, c_mu, depth, bulk_velocity):
    """u = sqrt(2k/3) n, duration = C0 T_L e"""
    with np.errstate(divide="ignore"):
        tl = np.where(omega > 0.0, 1.0 / (6.0 * c_mu * omega), np.inf)
    s = np.sqrt(2.0 * np.maximum(k, 0.0) / 3.0)
    alive = np.isfinite(tl)
    return {
        "u_x": np.where(alive, s * n_x, 0.0),
        "u_y": np.where(alive, s * n_y, 0.0),
        "u_z": np.where(alive, s * n_z, 0.0),
        "duration": np.where(alive, c0 * tl * e, np.inf),
    }


def eim_diffusivity(k, omega, nu_t, reynolds_stress, c0, c_mu, depth, bulk_velocity):
    """D = 2 k / 3 C0 T_L"""
    with np.errstate(divide="ignore"):
        tl = np.where(omega > 0.0, 1.0 / (6.0 * c_mu * omega), 0.0)
    return 2.0 * k / 3.0 * c0 * tl


def shifted_diffusivity(k, omega, nu_t, reynolds_stress, c0, c_mu, depth, bulk_velocity):
    """D = 2 k / 3 C0 T_L - 1e-4: negative in weak turbulence"""
    return eim_diffusivity(k, omega, nu_t, reynolds_stress, c0, c_mu, depth, bulk_velocity) - 1e-4


@pytest.fixture(scope="module", autouse=True)
def registered():
    saltus.register_rheology("ck_mu_i", mu_i, params=MU_I, limits=RHEOLOGY_LIMITS)
    saltus.register_rheology("ck_mu_offset", mu_i_offset, params=MU_I, limits=RHEOLOGY_LIMITS)
    saltus.register_rheology("ck_compacting", mu_i_compacting, params=MU_I, limits=RHEOLOGY_LIMITS)
    saltus.register_kinetic_theory("ck_chialvo", chialvo_sundaresan, params=KINETIC, limits=["dilute"],
                                   drag_dissipation="linear")
    saltus.register_kinetic_theory("ck_g0_offset", g0_offset, params=KINETIC, limits=["dilute"],
                                   drag_dissipation="linear")
    saltus.register_mixing_length("ck_li_sawamoto", li_sawamoto, params=LENGTH, limits=[("wall_length", "kappa")])
    saltus.register_mixing_length("ck_rough_wall", rough_wall, params=LENGTH, limits=[("wall_length", "kappa")])
    saltus.register_fluctuation("ck_eim", eim_draw, eim_diffusivity, params=EIM, variates=VARIATES,
                                needs=["k", "omega"], limits=["non_negative"])
    saltus.register_fluctuation("ck_shifted", eim_draw, shifted_diffusivity, params=EIM, variates=VARIATES,
                                needs=["k", "omega"], limits=["non_negative"])
    yield
    for family, names in [("granular", ["ck_mu_i", "ck_mu_offset", "ck_compacting", "ck_chialvo", "ck_g0_offset"]),
                          ("turbulence", ["ck_li_sawamoto", "ck_rough_wall"]),
                          ("fluctuation", ["ck_eim", "ck_shifted"])]:
        for name in names:
            saltus.unregister_closure(family, name)


@pytest.mark.parametrize(
    "family, name, limits",
    [
        ("granular", "ck_mu_i", ["limit static", "packing decreasing", "increasing"]),
        ("granular", "ck_chialvo", ["limit dilute"]),
        ("turbulence", "ck_li_sawamoto", ["limit wall"]),
        ("fluctuation", "ck_eim", ["non-negative"]),
    ],
)
def test_numpy_versions_of_the_built_in_laws_pass_with_their_declared_limits(family, name, limits):
    report = saltus.closure_check(family, {"type": name}, cases=64)
    assert report.passed, report.text
    names = [o["name"] for o in report.outcomes]
    assert names[:4] == ["documented", "toml round trip", "finite", "batch = scalar"], report.text
    assert names[4:] == limits, report.text


def failed(family, name):
    report = saltus.closure_check(family, {"type": name}, cases=64)
    assert not report.passed, report.text
    return {o["name"]: o for o in report.outcomes if not o["passed"]}, report.text


def test_a_friction_off_mu_s_at_rest_fails_the_static_limit():
    fails, text = failed("granular", "ck_mu_offset")
    assert set(fails) == {"limit static"}, text
    assert "mu does not tend to 0.35" in fails["limit static"]["summary"], text
    # shrunk to the parameters as given: the law is wrong at every parameter value
    assert fails["limit static"]["input"] == "parameters as given", text


def test_a_packing_that_grows_with_i_fails_with_the_shrunk_pair():
    fails, text = failed("granular", "ck_compacting")
    assert set(fails) == {"packing decreasing"}, text
    shown = fails["packing decreasing"]["input"]
    assert shown.startswith("x = ") and shown.endswith("parameters as given"), text
    x, dx = (float(v.split(")")[0]) for v in shown[len("x = "):].split("; ")[0].split(", x * (1 + "))
    # the pair lies above I = 0.5, where the packing turns
    assert x * (1.0 + dx) > 0.5, text


def test_a_g0_off_one_in_the_dilute_limit_fails():
    fails, text = failed("granular", "ck_g0_offset")
    assert set(fails) == {"limit dilute"}, text
    assert "g0 does not tend to 1" in fails["limit dilute"]["summary"], text


def test_a_mixing_length_with_a_roughness_offset_fails_the_wall_limit():
    fails, text = failed("turbulence", "ck_rough_wall")
    assert set(fails) == {"limit wall"}, text
    assert "l_m / z" in fails["limit wall"]["summary"], text


def test_a_negative_diffusivity_fails_with_the_shrunk_turbulence():
    fails, text = failed("fluctuation", "ck_shifted")
    assert set(fails) == {"non-negative"}, text
    o = fails["non-negative"]
    assert o["summary"].startswith("D = -"), text
    # shrunk: no turbulent kinetic energy at all
    assert o["input"].startswith("k = 0, "), text
