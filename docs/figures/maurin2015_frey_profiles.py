"""Maurin et al. 2015 figures 4-5: depth profiles of the Frey runs against the experiments.

    python3 docs/figures/maurin2015_frey_profiles.py SIM6_RUN SIM14_RUN SIM20_RUN \
        --exp YADE/examples/HydroForceEngine/validations/DEMCoupling/Maurinetal2015/expData \
        [--out docs/figures/maurin2015_frey_profiles.png]

SIMn_RUN is the output folder of `saltus run cases/maurin2015/frey_simN.toml` (its
`profiles.csv`). The measured profiles of Frey (2014) (solid fraction, particle velocity,
z in bead diameters from the mean elevation of the bottom's half-cylinders, the origin of
the scenes' column) are not in this repository: they come with the peer code's example of
these runs, files `Frey2014_EXP6.py`, `Frey2014_EXP14.py`, `Frey2014_EXP20.py` (arrays
`zData`, `alphasData`, `usData`), which `--exp` names. They are parsed as numbers, never
executed.

Printed per run, for the experiment and the run: the transport rate in beads/s (the
integral of phi v_p over the profile, times the channel width W = 6.5 mm, over the volume
of a bead), the elevations (in d) where phi falls through 0.4, 0.25, 0.1 and 0.02, the
elevation of the largest flux density, and the particle velocity at the bed top (phi =
0.25) and 1 d and 2 d above it. Needs numpy and matplotlib (the figure only).
"""

import argparse
import csv
import math
import os
import re

import numpy as np

D = 6.0e-3
WIDTH = 6.5e-3
BEAD = math.pi * D**3 / 6.0
RUNS = (6, 14, 20)
LEVELS = (0.4, 0.25, 0.1, 0.02)


def read_array(text, name):
    m = re.search(name + r"\s*=\s*array\(\[([^\]]*)\]\)", text)
    if m is None:
        raise SystemExit(f"no array `{name}` in the experimental file")
    return np.array([float(v) for v in m.group(1).replace("\n", " ").split(",") if v.strip()])


def experiment(folder, sim):
    path = os.path.join(folder, f"Frey2014_EXP{sim}.py")
    text = open(path).read()
    z, phi, vp = (read_array(text, n) for n in ("zData", "alphasData", "usData"))
    if not len(z) == len(phi) == len(vp):
        raise SystemExit(f"{path}: zData, alphasData and usData differ in length")
    return z, phi, vp


def simulation(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "profiles.csv"))))
    z = np.array([float(r["z"]) for r in rows]) / D
    phi = np.array([float(r["phi"]) for r in rows])
    vp = np.array([float(r["u_p"]) for r in rows])
    return z, phi, vp


def falls_through(z, phi, level):
    """Highest elevation where phi falls through `level` (linear between samples)."""
    above = np.nonzero(phi >= level)[0]
    if len(above) == 0:
        return float("nan")
    i = above[-1]
    if i + 1 >= len(z):
        return z[i]
    return z[i] + (z[i + 1] - z[i]) * (phi[i] - level) / (phi[i] - phi[i + 1])


def metrics(z, phi, vp):
    q = phi * vp
    integrate = getattr(np, "trapezoid", None) or np.trapz
    rate = integrate(q, z * D) * WIDTH / BEAD
    levels = [falls_through(z, phi, lv) for lv in LEVELS]
    top = levels[1]
    peak = z[int(np.argmax(q))]
    speeds = [float(np.interp(top + h, z, vp)) for h in (0.0, 1.0, 2.0)]
    return rate, levels, peak, speeds


def show(tag, m):
    rate, levels, peak, speeds = m
    lv = " ".join(f"{v:5.2f}" for v in levels)
    sp = " ".join(f"{v:5.3f}" for v in speeds)
    print(f"| {tag} | {rate:6.2f} | {lv} | {peak:5.2f} | {sp} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs=3, help="output folders of Sim6, Sim14 and Sim20")
    ap.add_argument("--exp", required=True, help="folder holding Frey2014_EXP{6,14,20}.py")
    ap.add_argument("--out", help="figure file")
    args = ap.parse_args()

    print("| profile | beads/s | z/d where phi = 0.4, 0.25, 0.1, 0.02 | z/d of the largest flux | v_p (m/s) at the bed top, +1 d, +2 d |")
    print("|---|---:|---|---:|---|")
    pairs = []
    for sim, run in zip(RUNS, args.runs):
        exp = experiment(args.exp, sim)
        ours = simulation(run)
        show(f"Exp{sim}", metrics(*exp))
        show(f"Sim{sim} ({os.path.basename(os.path.normpath(run))})", metrics(*ours))
        pairs.append((sim, exp, ours))

    if args.out:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(3, 3, figsize=(10, 10), sharey="row")
        for row, (sim, exp, ours) in zip(axes, pairs):
            (ze, pe, ve), (zs, ps, vs) = exp, ours
            lo, hi = ze.min() - 0.5, max(ze.max(), zs[ps > 1e-3].max() if (ps > 1e-3).any() else ze.max()) + 0.3
            keep = (zs >= lo) & (zs <= hi)
            for ax, (xe, xs, label) in zip(
                row,
                ((pe, ps, "phi"), (ve, vs, "v_p (m/s)"), (pe * ve, ps * vs, "q = phi v_p (m/s)")),
            ):
                ax.plot(xe, ze, "o", ms=3, mfc="none", color="k", label=f"Exp{sim} (Frey 2014)")
                ax.plot(xs[keep], zs[keep], "-", color="tab:red", label=f"Sim{sim}, saltus")
                ax.set_xlabel(label)
                ax.set_ylim(lo, hi)
                ax.grid(alpha=0.3)
            row[0].set_ylabel(f"Sim{sim}: z / d")
            row[0].legend(fontsize=8, loc="lower left")
        fig.suptitle("Frey runs (Maurin et al. 2015 table III): depth profiles against the experiments")
        fig.tight_layout()
        fig.savefig(args.out, dpi=110)
        print(f"figure: {args.out}")


if __name__ == "__main__":
    main()
