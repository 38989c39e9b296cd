"""Batch sedimentation of Pham Van Bang et al. (2008) from a saltus run: interfaces against
time and concentration profiles at the data's times, beside the measurements.

    saltus run cases/pham_van_bang2008/sedimentation.toml --out RUN_DIR
    python3 docs/figures/pham_van_bang2008_sedimentation.py RUN_DIR \
        [--data ../shared/data/pham_van_bang2008_sedimentation/csv] \
        [--out docs/figures/pham_van_bang2008_sedimentation.png]

The run's snapshots (`snapshots/index.csv`, one profile every 60 s, the scene's
`output.snapshot_interval`) are read at their own times, within 0.5 s of the data's (the
interfaces move by under 0.01 mm/s). The interfaces are those of the validation test
(`solvers/tests/sedimentation.rs`): the highest level where phi crosses phi0 / 2 = 0.25
(upper) and the first level from the bottom where it crosses 0.55 (lower). The data's
frame is 0.1 m above the column's bottom (z = z_data + 0.1).

Printed: for every data time, the two interfaces (run and data) and the RMS difference of
phi over the data's 70 points (each point compared with the run's phi interpolated to
its height). Needs numpy and matplotlib.
"""

import argparse
import csv
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]


def read_block(path):
    """A CSV of numbers after '#' comment lines, as a 2-D array."""
    rows = [line for line in path.read_text().splitlines() if line.strip() and not line.startswith("#")]
    return np.array([[float(x) for x in r.split(",")] for r in rows])


def interfaces(z, phi):
    """Upper (highest crossing of 0.25) and lower (first crossing of 0.55) interfaces."""

    def at(i, level):
        return z[i - 1] + (z[i] - z[i - 1]) * (phi[i - 1] - level) / (phi[i - 1] - phi[i])

    upper = next((at(i, 0.25) for i in range(len(z) - 1, 0, -1) if phi[i - 1] >= 0.25 > phi[i]), float("nan"))
    lower = next((at(i, 0.55) for i in range(1, len(z)) if phi[i - 1] >= 0.55 > phi[i]), float("nan"))
    return upper, lower


def snapshots(run):
    index = run / "snapshots" / "index.csv"
    if not index.is_file():
        sys.exit(f"{index}: missing (run the scene with output.snapshot_interval > 0)")
    out = []
    with index.open() as f:
        for row in csv.DictReader(f):
            with (run / "snapshots" / row["file"]).open() as g:
                cols = list(csv.DictReader(g))
            z = np.array([float(r["z"]) for r in cols])
            phi = np.array([float(r["phi"]) for r in cols])
            out.append((float(row["t"]), z, phi))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", type=pathlib.Path)
    ap.add_argument("--data", type=pathlib.Path, default=ROOT.parent / "shared/data/pham_van_bang2008_sedimentation/csv")
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "docs/figures/pham_van_bang2008_sedimentation.png")
    ap.add_argument("--times", default="120,300,600,900,1200,1500", help="profile times drawn (s)")
    a = ap.parse_args()
    try:
        t_data = read_block(a.data / "t_pvb.csv")[0]
        upper_data = read_block(a.data / "zint_pvb.csv")[0] + 0.1
        lower_data = read_block(a.data / "zint2_pvb.csv")[0] + 0.1
        conc = read_block(a.data / "as_pvb.csv")
        z_data = read_block(a.data / "z_pvb.csv") + 0.1
    except (OSError, ValueError, IndexError) as e:
        sys.exit(f"{a.data}: cannot read the data: {e}")
    snaps = [(0.0, None, None)] + snapshots(a.run)

    print(f"{'t (s)':>7} {'upper run':>10} {'data':>8} {'lower run':>10} {'data':>8} {'RMS phi':>8}")
    run_t, run_up, run_lo, rms = [], [], [], {}
    for k, t in enumerate(t_data):
        near = min(snaps[1:], key=lambda s: abs(s[0] - t))
        if t == 0.0 or abs(near[0] - t) > 0.5:
            continue
        _, z, phi = near
        up, lo = interfaces(z, phi)
        run_t.append(t)
        run_up.append(up)
        run_lo.append(lo)
        diff = np.interp(z_data[:, k], z, phi) - conc[:, k]
        rms[t] = float(np.sqrt(np.mean(diff**2)))
        print(f"{t:7.0f} {up:10.4f} {upper_data[k]:8.4f} {lo:10.4f} {lower_data[k]:8.4f} {rms[t]:8.4f}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5.2))
    ax.plot(t_data, upper_data, "o", mfc="none", color="C0", label="upper, data")
    ax.plot(t_data, lower_data, "s", mfc="none", color="C1", label="lower, data")
    ax.plot(run_t, run_up, "-", color="C0", label="upper, saltus")
    ax.plot(run_t, run_lo, "-", color="C1", label="lower, saltus")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("z [m]")
    ax.set_title("interfaces")
    ax.legend(loc="center right")
    times = [float(x) for x in a.times.split(",") if x.strip()]
    for i, t in enumerate(times):
        k = int(np.argmin(abs(t_data - t)))
        near = min(snaps[1:], key=lambda s: abs(s[0] - t_data[k]))
        color = f"C{i}"
        bx.plot(conc[:, k], z_data[:, k], ".", color=color)
        bx.plot(near[2], near[1], "-", color=color, label=f"t = {t_data[k]:.0f} s")
    bx.set_xlabel("phi [-]")
    bx.set_ylabel("z [m]")
    bx.set_ylim(0.0, 0.06)
    bx.set_title("concentration: saltus (lines), data (dots)")
    bx.legend(loc="upper right")
    fig.suptitle("Batch sedimentation, Pham Van Bang et al. 2008")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"figure: {a.out}")


if __name__ == "__main__":
    main()
