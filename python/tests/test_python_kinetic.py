"""A frictional-collisional kinetic-theory coefficient set written in Python
(saltus.register_kinetic_theory): the proposed model of Chassagne, Bonamy & Chauchat 2023
(table 1, right column), the built-in ``frictional_collisional`` at its defaults, in numpy
arithmetic with the per-element powers and the scalar tanh and arctan of Python's ``math``
(numpy's vectorised ``power`` may differ from the C library's in the last bit, which the
steady state of case 1 amplifies to a few 1e-10 in qs*). It reproduces Chassagne case 1's
qs* to 1e-10 and its profiles."""

import math

import numpy as np
import pytest

import saltus

CASE01 = "cases/chassagne2023/case01.toml"

SQRT_PI = 1.772_453_850_905_516
ETA_0 = 5.0 * SQRT_PI / 96.0  # dilute viscosity 5 sqrt(pi) / 96
KAPPA_0 = 225.0 * SQRT_PI / 576.0  # 2 kappa_0, dilute conductivity

# eq 3.3 (a0, a_max, delta), App. C (e_t), eqs 3.5-3.9 (c0, sigma)
PROPOSED = {"a0": 0.58, "a_max": 3.70, "delta": 0.54, "e_t": 0.0, "c0": 5.0, "sigma": 0.5}


def jenkins_zhang_f(mu_p, e, e_t):
    """f(mu_p) of e_eff = e - f (App. C eqs C1-C6, sliding threshold mu0 = 7/2 mu_p (1+e)/(1+e_t))"""
    if not mu_p > 0.0:
        return 0.0
    r = (1.0 + e_t) / (3.5 * (1.0 + e))
    mu0 = mu_p / r
    m2 = mu0 * mu0
    h = 0.5 * math.pi - math.atan(mu0)
    a1 = r * (2.0 * mu0 * h + 2.0 * m2 / (1.0 + m2) * (1.0 - 2.0 * r))
    a2 = 2.5 * r * (mu0 * h + (m2 - m2 * m2) / ((1.0 + m2) * (1.0 + m2)))
    b1_over_b2 = 2.0 * r * mu0 / (1.0 + m2) / (h + mu0 / (1.0 + m2))
    return 0.5 * (a1 - a2 * b1_over_b2)


def times_g0(a, g0):
    # an exactly-zero coefficient annihilates an infinite g0
    with np.errstate(invalid="ignore"):
        return np.where(a == 0.0, 0.0, a * g0)


def harmonic(kinetic, salt):
    # eqs 3.7 and 3.10: kinetic salt / (salt + |kinetic|), the kinetic part where salt = +inf
    den = salt + np.abs(kinetic)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(den > 0.0, kinetic * salt / den, 0.0)
    return np.where(np.isinf(salt), kinetic, mean)


def proposed(phi, sqrt_t, k_drag, a0, a_max, delta, e_t, c0, sigma, p0, phi_rlp, phi_max, static_friction,
             diameter, density, restitution, friction):
    """g0 of eqs 3.2-3.3, e_eff of App. C, F1-F4 of table 1 with the saltation of eqs 3.6-3.10"""
    phi = np.where(phi < 0.0, 0.0, phi)
    e, mu_p = restitution, friction
    # g0 = g0_CS + a(mu_p) phi^2 / (phi_max - phi)^{3/2}, +inf from phi_max on
    a = a0 + (a_max - a0) * math.tanh(mu_p / delta)
    q = 1.0 - phi
    with np.errstate(divide="ignore", invalid="ignore"):
        cs = np.where(phi >= 1.0, np.inf, (2.0 - phi) / (2.0 * q * q * q))
        gap = np.array([math.pow(x, 1.5) if x > 0.0 else 0.0 for x in (phi_max - phi).tolist()])
        g0 = np.where(phi >= phi_max, np.inf, cs + a * phi * phi / gap)
        inv_g0 = 1.0 / g0
    e_eff = max(e - jenkins_zhang_f(mu_p, e, e_t), 0.0)
    # Garzo & Dufty 1999 as printed in table 1, summed as A + B / g0 + C g0
    eta_den = 1.0 - 0.25 * (1.0 - e) * (1.0 - e) - 5.0 / 24.0 * (1.0 - e * e)
    eta_q = 0.4 * (1.0 + e) * (1.0 - 3.0 * e)
    kappa_den = (1.0 - 7.0 / 16.0 * (1.0 - e)) * (1.0 + e)
    kappa_r = 0.6 * (1.0 + e) * (1.0 + e) * (2.0 * e - 1.0)
    eta_k = ETA_0 * (inv_g0 - eta_q * phi) / eta_den
    kappa_k = KAPPA_0 * (inv_g0 + kappa_r * phi) / kappa_den
    s = 0.8 * (1.0 + e) * phi
    c = 0.8 / SQRT_PI * (1.0 + e) * phi * phi - ETA_0 * s * eta_q * phi / eta_den
    eta_cb = ETA_0 * s / eta_den + times_g0(c, g0)
    s = 1.2 * (1.0 + e) * phi
    c = 2.0 / SQRT_PI * (1.0 + e) * phi * phi + KAPPA_0 * s * kappa_r * phi / kappa_den
    kappa_cb = KAPPA_0 * s / kappa_den + times_g0(c, g0)
    # saltation (eq 3.6): eta_salt = rho_p phi sqrt(T) / (c0 d K), +inf without drag
    den = c0 * diameter * k_drag
    with np.errstate(divide="ignore", invalid="ignore"):
        eta_salt = np.where(den > 0.0, density * phi * np.where(sqrt_t > 0.0, sqrt_t, 0.0) / den, np.inf)
    return {
        "g0": g0,
        "f1": phi + times_g0(2.0 * (1.0 + e) * phi * phi, g0),
        "f2": harmonic(eta_k, eta_salt) + eta_cb,
        "f3": harmonic(kappa_k, eta_salt / sigma) + kappa_cb,
        "f4": times_g0(12.0 / SQRT_PI * (1.0 - e_eff * e_eff) * phi * phi, g0),
        "e_eff": np.full_like(phi, e_eff),
    }


@pytest.fixture(scope="module", autouse=True)
def python_kinetic():
    saltus.register_kinetic_theory("py_proposed", proposed, params=PROPOSED, saltation=True)
    yield
    saltus.unregister_closure("granular", "py_proposed")


def test_python_proposed_model_reproduces_case01(root):
    built_in = saltus.run(root / CASE01, out=False)
    python = saltus.run(root / CASE01, set={"closures.granular": {"type": "py_proposed"}}, out=False)
    q = built_in.summary["qs_star"]
    assert q > 0.5, built_in.summary
    assert abs(python.summary["qs_star"] - q) <= 1e-10 * q, (python.summary["qs_star"], q)
    for name in ["phi", "u_f"]:
        np.testing.assert_allclose(python.profiles[name], built_in.profiles[name], rtol=0, atol=1e-9, err_msg=name)
    # the grains' velocity where they are (in the dilute top, phi < 1e-2, round-off of the
    # two evaluations is not damped by the steady test), and their flux everywhere
    phi = built_in.profiles["phi"]
    dense = phi > 1e-2
    np.testing.assert_allclose(python.profiles["u_p"][dense], built_in.profiles["u_p"][dense], rtol=0, atol=1e-9)
    np.testing.assert_allclose(
        python.profiles["phi"] * python.profiles["u_p"], phi * built_in.profiles["u_p"], rtol=0, atol=1e-10
    )


def test_python_coefficients_equal_the_built_in_ones_and_diverge_at_phi_max():
    phi = np.array([0.0, 1e-6, 0.1, 0.3, 0.5, 0.6, 0.634, 0.635, 0.7])
    python = saltus.Closure("kinetic_theory", {"type": "py_proposed"}).evaluate(phi=phi)
    built_in = saltus.Closure("kinetic_theory", {"type": "frictional_collisional"}).evaluate(phi=phi)
    for name in ["g0", "f1", "f2", "f3", "f4"]:
        finite = np.isfinite(built_in[name])
        np.testing.assert_array_equal(np.isfinite(python[name]), finite, err_msg=name)
        np.testing.assert_allclose(python[name][finite], built_in[name][finite], rtol=1e-14, atol=0, err_msg=name)
    assert python["g0"][0] == 1.0 and np.isinf(python["g0"][-2:]).all()
