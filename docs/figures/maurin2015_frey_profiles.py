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

    python3 docs/figures/maurin2015_frey_profiles.py --windows RUN [--window 40]

instead reads the ParaView snapshots of one run (`solver.lagrangian.vtk_period`, in
RUN/vtk) and prints the same measures for each window of `--window` bead diameters along
the periodic cell (the measurements' window is 40 d long, the paper's figure 3), averaged
over all the snapshots: their mean, standard deviation and range, with the whole cell
over the same snapshots, and the range of phi inside the bed (3.1 to 6.6 d). The grains'
volumes are cut by the cells of the run's column exactly (sphere caps), as the solver's
averages are.
"""

import argparse
import base64
import csv
import glob
import math
import os
import re

import numpy as np

D = 6.0e-3
WIDTH = 6.5e-3
BEAD = math.pi * D**3 / 6.0
RUNS = (6, 14, 20)
LEVELS = (0.4, 0.25, 0.1, 0.02)


def read_text(path):
    try:
        with open(path) as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise SystemExit(f"{path}: cannot be read ({e})")


def numbers(path, what, values):
    """The finite numbers of `values`, or an exit naming the file and what they were."""
    try:
        a = np.array([float(v) for v in values])
    except ValueError as e:
        raise SystemExit(f"{path}: {what} holds a value that is not a number ({e})")
    if len(a) < 2:
        raise SystemExit(f"{path}: {what} needs at least two values, has {len(a)}")
    if not np.isfinite(a).all():
        raise SystemExit(f"{path}: {what} holds a value that is not finite")
    return a


def read_array(path, text, name):
    m = re.search(name + r"\s*=\s*array\(\[([^\]]*)\]\)", text)
    if m is None:
        raise SystemExit(f"{path}: no array `{name}` (zData, alphasData and usData are needed)")
    return numbers(path, name, [v for v in m.group(1).replace("\n", " ").split(",") if v.strip()])


def experiment(folder, sim):
    path = os.path.join(folder, f"Frey2014_EXP{sim}.py")
    text = read_text(path)
    z, phi, vp = (read_array(path, text, n) for n in ("zData", "alphasData", "usData"))
    if not len(z) == len(phi) == len(vp):
        raise SystemExit(f"{path}: zData, alphasData and usData differ in length")
    return z, phi, vp


def simulation(folder):
    path = os.path.join(folder, "profiles.csv")
    rows = list(csv.DictReader(read_text(path).splitlines()))
    missing = [c for c in ("z", "phi", "u_p") if rows and c not in rows[0]]
    if missing:
        raise SystemExit(f"{path}: no column {', '.join(missing)} (a saltus DEM run's profiles.csv is needed)")
    z, phi, vp = (numbers(path, f"column {c}", [r[c] for r in rows]) for c in ("z", "phi", "u_p"))
    return z / D, phi, vp


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


def vtp_arrays(path):
    """The Float64 arrays of a saltus VTK PolyData file (base64, UInt64 byte count)."""
    text = read_text(path)
    out = {}
    pattern = r'<DataArray type="Float64" Name="(\w+)" NumberOfComponents="(\d)" format="binary">([^<]*)</DataArray>'
    for name, comps, data in re.findall(pattern, text):
        raw = base64.b64decode(data.strip())
        count = int(np.frombuffer(raw[:8], dtype="<u8")[0])
        out[name] = np.frombuffer(raw[8 : 8 + count], dtype="<f8").reshape(-1, int(comps))
    return out


def below(zc, r, h):
    """Volume of the spheres of centres zc and radii r below the heights h."""
    s = np.clip(h - (zc - r), 0.0, 2.0 * r)
    return math.pi * s * s * (3.0 * r - s) / 3.0


def windows(run, window, length):
    """Solid volume and streamwise momentum per window of the cell and per column cell,
    summed over the run's snapshots; the column's cell height and the snapshot count."""
    columns = sorted(glob.glob(os.path.join(run, "vtk", "column_*.vtp")))
    snaps = sorted(glob.glob(os.path.join(run, "vtk", "particles_*.vtp")))
    if not columns or not snaps:
        raise SystemExit(f"{run}/vtk holds no snapshots: run with --set solver.lagrangian.vtk_period=T")
    zc = vtp_arrays(columns[0]).get("Points", np.zeros((0, 3)))[:, 2]
    if len(zc) < 2:
        raise SystemExit(f"{columns[0]}: not a saltus column snapshot (two cells at least are needed)")
    dz = zc[1] - zc[0]
    base, n = zc[0] - dz / 2.0, len(zc)
    count = max(1, int(round(length / window)))
    vol, mom = np.zeros((count, n)), np.zeros((count, n))
    for path in snaps:
        a = vtp_arrays(path)
        if not {"Points", "velocity", "radius"} <= a.keys():
            raise SystemExit(f"{path}: not a saltus particle snapshot (Points, velocity and radius are needed)")
        mobile = a["fixed"][:, 0] == 0 if "fixed" in a else slice(None)
        p, vx, r = a["Points"][mobile], a["velocity"][mobile, 0], a["radius"][mobile, 0]
        if len(r) == 0:
            continue
        k = np.minimum((np.mod(p[:, 0], length) / (length / count)).astype(int), count - 1)
        z = p[:, 2] - base
        cells = np.floor((z - r) / dz).astype(int)[:, None] + np.arange(int(np.ceil(2 * r.max() / dz)) + 2)
        w = below(z[:, None], r[:, None], (cells + 1) * dz) - below(z[:, None], r[:, None], cells * dz)
        ok = (cells >= 0) & (cells < n) & (w > 0)
        kk = np.broadcast_to(k[:, None], cells.shape)
        np.add.at(vol, (kk[ok], cells[ok]), w[ok])
        np.add.at(mom, (kk[ok], cells[ok]), (w * vx[:, None])[ok])
    return vol, mom, dz, len(snaps), length / count


def window_report(run, window):
    import tomllib

    path = os.path.join(run, "scene.toml")
    try:
        length = float(tomllib.load(open(path, "rb"))["solver"]["lagrangian"]["length"])
    except (OSError, KeyError, ValueError, tomllib.TOMLDecodeError) as e:
        raise SystemExit(f"{path}: no solver.lagrangian.length ({e})")
    if not (math.isfinite(length) and length > 0.0):
        raise SystemExit(f"{path}: solver.lagrangian.length = {length}, not a cell length")
    if window * D > length:
        raise SystemExit(f"--window {window:g} d is longer than the cell ({length / D:g} d)")
    vol, mom, dz, snaps, wl = windows(run, window * D, length)
    z = (np.arange(vol.shape[1]) + 0.5) * dz / D
    bed = (z > 3.1) & (z < 6.6)

    def profile(v, mo, length):
        phi = v / (snaps * length * WIDTH * dz)
        return z, phi, np.where(v > 0, mo / np.where(v > 0, v, 1.0), 0.0)

    per = [profile(vol[k], mom[k], wl) for k in range(vol.shape[0])]
    ms = [metrics(*pr) for pr in per]
    width = np.array([m[1][2] - m[1][0] for m in ms])
    top = np.array([m[1][1] for m in ms])
    speed = np.array([m[3] for m in ms])
    lo = np.array([pr[1][bed].min() for pr in per])
    hi = np.array([pr[1][bed].max() for pr in per])
    print(f"{vol.shape[0]} windows of {wl / D:.0f} d over {snaps} snapshots")
    print("| profile | phi 0.4 -> 0.1 (d) | bed top, z/d at phi = 0.25 | v_p at the bed top (m/s) | v_p 2 d above it | phi in the bed (3.1-6.6 d) |")
    print("|---|---|---|---|---|---|")
    print(
        f"| windows: mean +- sd [range] | {width.mean():.2f} +- {width.std():.2f} [{width.min():.2f}, {width.max():.2f}]"
        f" | {top.mean():.2f} +- {top.std():.2f} | {speed[:, 0].mean():.3f} +- {speed[:, 0].std():.3f}"
        f" [{speed[:, 0].min():.3f}, {speed[:, 0].max():.3f}] | {speed[:, 2].mean():.3f} +- {speed[:, 2].std():.3f}"
        f" | {lo.mean():.2f}-{hi.mean():.2f} on average; widest {lo.min():.2f}-{hi.max():.2f} |"
    )
    whole = profile(vol.sum(0), mom.sum(0), wl * vol.shape[0])
    _, lv, _, sp = metrics(*whole)
    print(
        f"| the whole cell | {lv[2] - lv[0]:.2f} | {lv[1]:.2f} | {sp[0]:.3f} | {sp[2]:.3f}"
        f" | {whole[1][bed].min():.2f}-{whole[1][bed].max():.2f} |"
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*", help="output folders of Sim6, Sim14 and Sim20")
    ap.add_argument("--exp", help="folder holding Frey2014_EXP{6,14,20}.py")
    ap.add_argument("--out", help="figure file")
    ap.add_argument("--windows", metavar="RUN", help="window statistics from RUN's snapshots instead")
    ap.add_argument("--window", type=float, default=40.0, help="window length in bead diameters (default 40)")
    args = ap.parse_args()
    if args.windows:
        if not (math.isfinite(args.window) and args.window >= 1.0):
            ap.error(f"--window {args.window}: a window of at least 1 bead diameter is allowed")
        window_report(args.windows, args.window)
        return
    if len(args.runs) != 3 or not args.exp:
        ap.error("give the three run folders (Sim6, Sim14, Sim20) and --exp, or --windows RUN")

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
