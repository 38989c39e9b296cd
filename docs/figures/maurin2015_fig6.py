"""Maurin et al. 2015 figure 6 from saltus runs: table, 3/2-power fits, figure.

    python3 docs/figures/maurin2015_fig6.py RUNS_DIR [--out docs/figures/maurin2015_fig6.png]
        [--mpm ../shared/data/mpm1948_recking2010/Meyer-Peter_Muller_1948_data.csv]

RUNS_DIR holds one `saltus run` output folder per point, named `<series>_<nominal theta>`
(e.g. `drw_0.1`, `nodrw_0.1`; docs/validation.md "Figure 6" gives
the commands), or is the folder of `saltus sweep cases/maurin2015/figure6_sweep*.toml`
(each point's window then starts at its own `stats_start` if that is after `--t0`). For each point: qs* as the mean of block means of the `qs_star` column of
`timeseries.csv` over the averaging window [t0, t1) (blocks of `--block` s, their standard
error), and theta* the summary's `shields_turbulent` (the paper's Shields number from the
largest Reynolds shear stress, section IV).

The fit is the paper's form (figure 6 caption, Wilson 1987): qs* = a (theta* - theta_c)^{3/2}
by least squares over the points with qs* > `--qmin`: for each theta_c on a fine grid below
the smallest fitted theta*, a is the linear least-squares slope, and the pair with the
smallest residual is kept. The same fit with a fixed at Wilson's 11.8 is printed too, and
the fit weighted by the points' 1/se^2 with the standard errors of a and theta_c (the
weighting and errors of `saltus sweep`'s `sweep_fit.csv`).
`--late T` adds the mean over [T, t1) (default 60 s: the second half of the window), with
its block error, and the same fits on it: the runs drift upwards over their window (the
bed loosens slowly), so the late mean is the nearer estimate of the equilibrium rate and
the difference between the two the drift. `--save FILE` writes the per-point table
(series, nominal theta, theta*, qs*, its standard error, blocks, theta, the late mean and
its standard error) as CSV; `--table FILE` reads such a table instead of
RUNS_DIR (pass `-` for RUNS_DIR; with both, a run folder replaces the table's row of its
point), so that a sweep run in several parts, or its
committed table (`docs/figures/maurin2015_fig6_30d.csv`), redraws without the run folders.
Needs numpy and matplotlib (the figure only).
"""

import argparse
import csv
import json
import math
import os

import numpy as np


def block_mean(folder, t0, t1, block):
    rows = list(csv.DictReader(open(os.path.join(folder, "timeseries.csv"))))
    t = np.array([float(r["t"]) for r in rows])
    q = np.array([float(r["qs_star"]) for r in rows])
    means = []
    s = t0
    while s + block <= t1 + 1e-9:
        m = (t >= s) & (t < s + block)
        if m.any():
            means.append(q[m].mean())
        s += block
    means = np.array(means)
    err = means.std(ddof=1) / math.sqrt(len(means)) if len(means) > 1 else float("nan")
    return means.mean(), err, len(means)


def fit(theta, qs, qmin):
    keep = qs > qmin
    th, q = theta[keep], qs[keep]
    if len(th) < 3:
        return None
    grid = np.linspace(0.0, th.min() - 1e-9, 40001)
    best = None
    for tc in grid:
        x = (th - tc) ** 1.5
        a = (x @ q) / (x @ x)
        r = float(((q - a * x) ** 2).sum())
        if best is None or r < best[2]:
            best = (a, tc, r)
    wil = min(grid, key=lambda tc: float(((q - 11.8 * (th - tc) ** 1.5) ** 2).sum()))
    rw = float(((q - 11.8 * (th - wil) ** 1.5) ** 2).sum())
    n = len(th)
    return {"a": best[0], "theta_c": best[1], "rms": math.sqrt(best[2] / n), "n": n,
            "theta_c_wilson": wil, "rms_wilson": math.sqrt(rw / n)}


def run_folders(runs, t0):
    """(name, folder, series, nominal theta, window start) of each point under `runs`:
    folders named `<series>_<nominal theta>`, or the points of a `saltus sweep` folder
    (its `sweep.json`: the series is the label of the axis other than `theta`, `none`
    written `nodrw`; each point's window starts at its scene's `stats_start` when that is
    later than `t0`, as at the first point of a warm-started chain)."""
    if runs == "-":
        return []
    manifest = os.path.join(runs, "sweep.json")
    if not os.path.isfile(manifest):
        out = []
        for name in sorted(os.listdir(runs)):
            if "_" in name:
                tag, nominal = name.rsplit("_", 1)
                out.append((name, os.path.join(runs, name), tag, nominal, t0))
        return out
    import tomllib
    m = json.load(open(manifest))
    labels = {a["name"]: dict(zip(map(json.dumps, a["values"]), a["labels"])) for a in m["axes"]}
    out = []
    for p in m["points"]:
        folder = os.path.join(runs, p["dir"])
        others = [labels[k][json.dumps(v)] for k, v in p["values"].items() if k != "theta"]
        tag = "_".join("nodrw" if t == "none" else t for t in others) or "sweep"
        start = t0
        scene = os.path.join(folder, "scene.toml")
        if os.path.isfile(scene):
            lag = tomllib.load(open(scene, "rb")).get("solver", {}).get("lagrangian", {})
            start = max(t0, float(lag.get("stats_start", t0)))
        out.append((p["dir"], folder, tag, str(p["values"]["theta"]), start))
    return out


def weighted_fit(theta, qs, se, qmin):
    """The fit of `fit` weighted by 1/se^2, with the standard errors of a and theta_c from
    the covariance (J^T W J)^-1 scaled by the reduced chi^2 (as `saltus sweep`'s
    `sweep_fit.csv`): over the points with qs* > qmin and a positive error."""
    keep = (qs > qmin) & (se > 0) & np.isfinite(se)
    th, q, w = theta[keep], qs[keep], 1.0 / se[keep] ** 2
    n = len(th)
    if n < 3:
        return None
    grid = np.linspace(0.0, th.min() - 1e-9, 40001)
    best = None
    for tc in grid:
        x = (th - tc) ** 1.5
        a = (w * x) @ q / ((w * x) @ x)
        r = float((w * (q - a * x) ** 2).sum())
        if best is None or r < best[2]:
            best = (a, tc, r)
    a, tc, chi2 = best
    s = th - tc
    jac = np.stack([s ** 1.5, -1.5 * a * s ** 0.5], axis=1)
    cov = np.linalg.inv(jac.T @ (w[:, None] * jac)) * chi2 / (n - 2)
    return {"a": a, "a_se": math.sqrt(cov[0, 0]), "theta_c": tc, "theta_c_se": math.sqrt(cov[1, 1]),
            "n": n, "chi2_red": chi2 / (n - 2)}


def show_weighted(label, f, qmin):
    """Print one fit of `weighted_fit`."""
    if f:
        print(f"{label}, {f['n']} points with qs* > {qmin:g}, weighted by 1/se^2: "
              f"a = {f['a']:.2f} +- {f['a_se']:.2f}, theta_c = {f['theta_c']:.4f} +- {f['theta_c_se']:.4f} "
              f"(reduced chi^2 {f['chi2_red']:.2f})")


def show_fit(label, f, qmin):
    """Print one fit of `fit` (nothing when there were too few points to fit)."""
    if f:
        print(f"{label}, {f['n']} points with qs* > {qmin:g}: a = {f['a']:.2f}, "
              f"theta_c = {f['theta_c']:.4f} (rms {f['rms']:.3g}); a = 11.8 fixed: "
              f"theta_c = {f['theta_c_wilson']:.4f} (rms {f['rms_wilson']:.3g})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs")
    ap.add_argument("--t0", type=float, default=10.0)
    ap.add_argument("--t1", type=float, default=110.0)
    ap.add_argument("--block", type=float, default=10.0)
    ap.add_argument("--qmin", type=float, default=1e-3)
    ap.add_argument("--late", type=float, default=60.0)
    ap.add_argument("--out")
    ap.add_argument("--mpm")
    ap.add_argument("--save")
    ap.add_argument("--table", action="append", default=[])
    args = ap.parse_args()

    series = {}
    for table in args.table:
        for r in csv.DictReader(open(table)):
            series.setdefault(r["series"], []).append(
                (float(r["nominal"]), float(r["theta_star"]), float(r["qs_star"]), float(r["stderr"]),
                 int(r["blocks"]), float(r["theta"]),
                 float(r.get("qs_star_late") or "nan"), float(r.get("stderr_late") or "nan")))
    for name, folder, tag, nominal, t0 in run_folders(args.runs, args.t0):
        if not os.path.isfile(os.path.join(folder, "summary.json")):
            continue
        s = json.load(open(os.path.join(folder, "summary.json")))
        if s.get("ending") != "end_time":
            print(f"skipped {name}: it ended with {s.get('ending')!r}, not at its end time")
            continue
        m, e, nb = block_mean(folder, t0, args.t1, args.block)
        ml, el, _ = block_mean(folder, args.late, args.t1, args.block)
        # a run folder replaces a table's row of the same point: never one point twice
        pts = [p for p in series.get(tag, []) if p[0] != float(nominal)]
        series[tag] = pts + [(float(nominal), s["shields_turbulent"], m, e, nb, s["shields"], ml, el)]

    if args.save:
        with open(args.save, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["series", "nominal", "theta_star", "qs_star", "stderr", "blocks", "theta",
                        "qs_star_late", "stderr_late"])
            for tag, pts in sorted(series.items()):
                for p in sorted(pts):
                    late = [f"{v:.6g}" if math.isfinite(v) else "" for v in p[6:8]]
                    w.writerow([tag, p[0], f"{p[1]:.6g}", f"{p[2]:.6g}", f"{p[3]:.6g}", p[4], f"{p[5]:.6g}"] + late)

    fits = {}
    for tag, pts in sorted(series.items()):
        pts.sort()
        print(f"\n{tag}: nominal theta | theta* | qs* +- stderr ({args.block:g}-s blocks, "
              f"{args.t0:g}-{args.t1:g} s) | qs* +- stderr ({args.late:g}-{args.t1:g} s) | "
              f"theta (largest fluid stress)")
        for p in pts:
            print(f"| {p[0]:g} | {p[1]:.4f} | {p[2]:.4g} +- {p[3]:.2g} | {p[6]:.4g} +- {p[7]:.2g} | {p[5]:.4f} |")
        theta_star = np.array([p[1] for p in pts])
        f = fit(theta_star, np.array([p[2] for p in pts]), args.qmin)
        fits[tag] = f
        show_fit(f"fit over the {args.t0:g}-{args.t1:g} s means", f, args.qmin)
        show_weighted(f"fit over the {args.t0:g}-{args.t1:g} s means",
                      weighted_fit(theta_star, np.array([p[2] for p in pts]), np.array([p[3] for p in pts]),
                                   args.qmin), args.qmin)
        late = np.array([p[6] for p in pts])
        if not np.isfinite(late).all():
            print(f"no late fit: {int((~np.isfinite(late)).sum())} point(s) without a late mean "
                  f"(a table written before --late, or a window shorter than one block)")
        else:
            show_fit(f"fit over the late means ({args.late:g}-{args.t1:g} s)", fit(theta_star, late, args.qmin), args.qmin)

    if not args.out:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, (ax, lin) = plt.subplots(1, 2, figsize=(10, 4.2))
    styles = {"drw": ("s", "k", "k", "with the DRW"), "nodrw": ("s", "none", "k", "without the DRW")}
    for tag, pts in sorted(series.items()):
        mk, fc, ec, label = styles.get(tag, ("o", "none", "C0", tag))
        th = np.array([p[1] for p in pts])
        q = np.array([p[2] for p in pts])
        e = np.array([p[3] for p in pts])
        for a_ in (ax, lin):
            a_.errorbar(th, q, yerr=e, fmt=mk, mfc=fc, mec=ec, ecolor=ec, label=f"saltus, {label}")
        f = fits.get(tag)
        if f:
            x = np.linspace(f["theta_c"], th.max() * 1.05, 200)
            ls = "-" if tag == "drw" else "--"
            lab = f"fit {f['a']:.1f} (theta* - {f['theta_c']:.3f})^1.5"
            for a_ in (ax, lin):
                a_.plot(x, f["a"] * (x - f["theta_c"]) ** 1.5, ls, color="0.3", lw=1, label=lab)
    x = np.linspace(0.04, 0.5, 200)
    ax.plot(x, 11.8 * (x - 0.04) ** 1.5, color="0.7", lw=2, label="Wilson 11.8 (theta - 0.04)^1.5")
    if args.mpm and os.path.isfile(args.mpm):
        rows = list(csv.DictReader(open(args.mpm)))
        th = [float(r["Shields stress"]) for r in rows]
        q = [float(r["dimensionless bedload flux per unit width"]) for r in rows]
        ax.plot(th, q, "+", color="C3", label="Meyer-Peter & Muller 1948 (Recking 2010)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(0.02, 0.6)
    ax.set_xticks([0.02, 0.05, 0.1, 0.2, 0.5])
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_ylim(1e-4, 10)
    ax.set_xlabel("theta* (largest Reynolds shear stress)")
    ax.set_ylabel("qs*")
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title("Maurin et al. 2015 fig. 6 set-up, 100 s averages")
    lin.set_xlim(0.0, 0.2)
    lin.set_ylim(-0.01, 0.4)
    lin.set_xlabel("theta*")
    lin.set_ylabel("qs*")
    lin.set_title("near the threshold (linear)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
