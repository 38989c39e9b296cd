"""Bed-aligned comparison of a saltus run of case MB (Revil-Baudard et al. 2015) with the
measured profiles: the data are shifted so that their phi = 0.3 level meets the run's
(the DEM's packed bed settles and erodes, so its bed top is not the scene's bed_height),
then the run's phi and u_f are interpolated linearly at the data's levels.

    saltus run cases/revil_baudard2015/mobile_bed_dem_k_omega_eim.toml --out RUN
    python3 docs/figures/revil_baudard2015_bed_aligned.py RUN \
        [--data ../shared/data/revil_baudard2015_sheetflow] [--out FIGURE.png]

Printed: the shift, RMS phi and RMS u_f over the data's points, the surface velocity
against the largest measured one, and the Reynolds stress tau_t / rho_f 1-5 cm above the
phi = 0.3 level beside the measured R_xz. With --out, a figure of the three profiles
against the shifted data (needs matplotlib). Needs numpy.
"""

import argparse
import csv
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]


def level(z, phi, value):
    """Highest level where phi falls through `value`, linear between centres."""
    for i in range(len(z) - 1, 0, -1):
        if phi[i - 1] >= value > phi[i]:
            return z[i - 1] + (z[i] - z[i - 1]) * (phi[i - 1] - value) / (phi[i - 1] - phi[i])
    return float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", type=pathlib.Path)
    ap.add_argument("--data", type=pathlib.Path, default=ROOT.parent / "shared/data/revil_baudard2015_sheetflow")
    ap.add_argument("--rho-f", type=float, default=1000.0)
    ap.add_argument("--out", type=pathlib.Path)
    a = ap.parse_args()
    try:
        ph = np.loadtxt(a.data / "Revil-Baudard2015_phi.txt")
        ur = np.loadtxt(a.data / "Revil-Baudard2015_uRxz.txt")
        with (a.run / "profiles.csv").open() as f:
            rows = list(csv.DictReader(f))
    except (OSError, ValueError) as e:
        sys.exit(f"cannot read the run or the data: {e}")

    def col(name):
        return np.array([float(r[name]) if r.get(name) else np.nan for r in rows])

    z, phi, uf, tau = col("z"), col("phi"), col("u_f"), col("tau_t")
    run03, data03 = level(z, phi, 0.3), level(ph[:, 0], ph[:, 1], 0.3)
    shift = run03 - data03
    rms_phi = np.sqrt(np.mean((np.interp(ph[:, 0] + shift, z, phi) - ph[:, 1]) ** 2))
    rms_u = np.sqrt(np.mean((np.interp(ur[:, 0] + shift, z, uf) - ur[:, 1]) ** 2))
    print(f"phi = 0.3 at z = {run03:.4f} m (run), {data03:.4f} m (data frame): shift {shift:.4f} m")
    print(f"RMS phi {rms_phi:.4f}, RMS u_f {rms_u:.4f} m/s over the data's points")
    print(f"surface velocity {uf[-1]:.3f} m/s, largest measured {ur[:, 1].max():.3f} m/s")
    for dz in (0.01, 0.02, 0.03, 0.05):
        run = np.interp(run03 + dz, z, tau) / a.rho_f
        data = np.interp(data03 + dz, ur[:, 0], ur[:, 2])
        print(f"{100 * dz:.0f} cm above phi = 0.3: tau_t / rho_f {run:.5f} m^2/s^2, measured R_xz {data:.5f}")
    if a.out is None:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(12, 5.2), sharey=True)
    h = z - run03
    axes[0].plot(phi, h, "-", label="saltus")
    axes[0].plot(ph[:, 1], ph[:, 0] - data03, "o", mfc="none", label="data")
    axes[0].set_xlabel("phi [-]")
    axes[1].plot(uf, h, "-", label="saltus u_f")
    axes[1].plot(ur[:, 1], ur[:, 0] - data03, "o", mfc="none", label="data")
    axes[1].set_xlabel("u [m/s]")
    axes[2].plot(tau / a.rho_f, h, "-", label="saltus tau_t / rho_f")
    axes[2].plot(ur[:, 2], ur[:, 0] - data03, "o", mfc="none", label="data R_xz")
    axes[2].set_xlabel("Reynolds stress [m^2/s^2]")
    axes[0].set_ylabel("z above the phi = 0.3 level [m]")
    for ax in axes:
        ax.legend()
        ax.grid(alpha=0.3)
    axes[0].set_ylim(-0.03, 0.12)
    fig.suptitle(f"Case MB, bed-aligned: RMS phi {rms_phi:.3f}, RMS u_f {rms_u:.3f} m/s")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"figure: {a.out}")


if __name__ == "__main__":
    main()
