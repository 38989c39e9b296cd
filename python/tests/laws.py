"""The numpy laws the Python-face tests register: mu(I) with its inverse in the built-in
`mu_i`'s arithmetic, and the eddy interaction model's mean-field diffusivity."""

import numpy as np

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


def eim_diffusivity(k, omega, nu_t, reynolds_stress, c0, c_mu, depth, bulk_velocity):
    """D = 2 k / 3 C0 T_l"""
    with np.errstate(divide="ignore", invalid="ignore"):
        tl = 1.0 / (6.0 * c_mu * omega)
        ok = np.isfinite(omega) & (omega > 0.0) & np.isfinite(tl) & np.isfinite(k) & (k > 0.0)
        return np.where(ok, 2.0 * k / 3.0 * c0 * tl, 0.0)
