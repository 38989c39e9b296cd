"""Profiles of continuum runs against the seed-to-seed scatter of DEM runs of one scene.

    python3 docs/figures/seed_scatter.py --dem DEM_SEED1 DEM_SEED2 [...] --run NAME=DIR [...]
        [--phi-min 0.01] [--moving 0.05] [--smooth H] [--align]

Each folder is a `saltus run` output (its `profiles.csv` and `summary.json`). The DEM
seeds are taken on the first seed's cells (each DEM fits its column to its own deposit, so
the others are interpolated linearly in z, up to the lowest top); their cell-by-cell mean
is the reference, and the standard deviation
of one seed about the true mean is estimated cell by cell from the seeds (for two seeds
|s1 - s2| / sqrt(2)). Each continuum run's profile is interpolated linearly in z onto the
DEM's cells. Over the cells where the grains move (the seed mean's phi above `--phi-min`
and its u_p above `--moving` times its largest u_p where phi is), the script prints, for
phi and u_p:

* `seed sd`: the RMS over those cells of the seeds' standard deviation, the scatter one
  DEM run carries;
* for each seed and each continuum run, the RMS of its difference from the seed mean.

A continuum profile "within the DEM's seed-to-seed scatter" has an RMS difference from the
seed mean no larger than `seed sd` (a further DEM seed would differ from the mean by about
that much). qs* of every run is printed beside, with the DEM seeds' mean and the spread.
Then the same differences against the first seed alone, over its own moving cells: the
measure of `saltus compare`'s `precision.csv` (`moving_rms_phi`, `moving_rms_u_p`), where
a continuum run no further from that seed than the other seeds are has a bias no larger
than one seed's standard deviation.

`--smooth H` first weights every profile (DEM seeds and continuum runs alike) with Fry et
al. 2024's Gaussian of h_g = H grain diameters (their eq 11, normalised over the column; as `saltus compare` does with `[reference] smooth`):
phi and the flux phi u_p are smoothed, u_p is their ratio. A DEM bed in a small cell
stacks its grains in layers about a diameter apart, a structure a continuum model has no
term for; the smoothing takes it out of both before they are compared. `--align` takes
every profile against the distance above its own bed surface, the level below which 1 %
of its flux flows (as `saltus compare` does for its RMS columns), instead of at the same
height.
Needs numpy.
"""

import argparse
import csv
import json
import math
import os

import numpy as np


def profiles(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "profiles.csv"))))
    return {k: np.array([float(r[k]) if r[k] != "" else math.nan for r in rows]) for k in rows[0]}


def summary(folder):
    return json.load(open(os.path.join(folder, "summary.json")))


def diameter(folder):
    import tomllib
    with open(os.path.join(folder, "scene.toml"), "rb") as f:
        return float(tomllib.load(f)["particles"]["diameter"])


def prepared(p, smooth_m, align):
    """phi and u_p of one run, smoothed with Fry's eq-11 Gaussian of width smooth_m (m) and
    taken against the distance above the bed surface if align."""
    z, phi = p["z"], np.nan_to_num(p["phi"])
    flux = phi * np.nan_to_num(p["u_p"])
    if smooth_m > 0:
        w = np.exp(-(((z[:, None] - z[None, :]) / smooth_m) ** 2)) * np.gradient(z)[None, :]
        w /= w.sum(axis=1, keepdims=True)
        phi, flux = w @ phi, w @ flux
    # where no grain is (after smoothing), the run's own u_p: a continuum's is defined there
    u_p = np.where(phi > 1e-9, flux / np.maximum(phi, 1e-9), np.nan_to_num(p["u_p"]))
    shift = 0.0
    if align:
        dz = np.gradient(z)
        q = np.concatenate([[0.0], np.cumsum(np.clip(flux, 0.0, None) * dz)])
        faces = np.concatenate([[z[0] - 0.5 * dz[0]], z + 0.5 * dz])
        shift = float(np.interp(0.01 * q[-1], q, faces))
    return {"z": z - shift, "phi": phi, "u_p": u_p}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dem", nargs="+", required=True)
    ap.add_argument("--run", action="append", default=[], help="NAME=DIR of a continuum run")
    ap.add_argument("--phi-min", type=float, default=0.01)
    ap.add_argument("--moving", type=float, default=0.05)
    ap.add_argument("--smooth", type=float, default=0.0, help="Gaussian h_g in grain diameters (Fry eq 11)")
    ap.add_argument("--align", action="store_true", help="against the distance above each bed surface")
    args = ap.parse_args()
    if len(args.dem) < 2:
        ap.error("two DEM seeds at least: the scatter is measured between them")

    h = args.smooth * diameter(args.dem[0])
    load = lambda folder: prepared(profiles(folder), h, args.align)  # noqa: E731
    seeds = [load(d) for d in args.dem]
    z = seeds[0]["z"]
    # a DEM fits its column to its own deposit: the other seeds onto the first one's cells
    top = min(s["z"].max() for s in seeds)
    keep = z <= top
    z = z[keep]
    seeds = [{c: (np.interp(z, s["z"], s[c]) if i else s[c][keep]) for c in ("z", "phi", "u_p")}
             for i, s in enumerate(seeds)]
    mean = {c: np.mean([s[c] for s in seeds], axis=0) for c in ("phi", "u_p")}
    sd = {c: np.std([s[c] for s in seeds], axis=0, ddof=1) for c in ("phi", "u_p")}
    grains = mean["phi"] > args.phi_min
    top_mean = np.nanmax(np.where(grains, mean["u_p"], np.nan))
    moving = grains & (mean["u_p"] > args.moving * top_mean)
    n = int(moving.sum())
    if n == 0:
        raise SystemExit("no cell where the grains move: lower --phi-min or --moving")
    lo, hi = z[moving].min(), z[moving].max()
    print(f"cells where the grains move: {n} (z {lo:.5g}-{hi:.5g} m; seed mean phi > {args.phi_min:g}, "
          f"u_p > {args.moving:g} x {top_mean:.4g} m/s, the largest u_p where phi is)")

    def rms(v):
        return math.sqrt(float(np.mean(v[moving] ** 2)))

    q = [summary(d).get("qs_star") for d in args.dem]
    qm = float(np.mean(q))
    print(f"DEM seeds qs*: {', '.join(f'{v:.4g}' for v in q)}; mean {qm:.4g}, "
          f"sd {float(np.std(q, ddof=1)):.3g}")
    print("| run | qs* | qs* / seed mean - 1 | RMS phi | RMS u_p (m/s) |")
    print("|---|---|---|---|---|")
    print(f"| seed sd (the scatter of one DEM run) | | | {rms(sd['phi']):.4f} | {rms(sd['u_p']):.4f} |")
    for d, s, v in zip(args.dem, seeds, q):
        print(f"| DEM {d} | {v:.4g} | {v / qm - 1:+.1%} | {rms(s['phi'] - mean['phi']):.4f} | "
              f"{rms(s['u_p'] - mean['u_p']):.4f} |")
    for spec in args.run:
        name, _, folder = spec.partition("=")
        p = load(folder)
        v = summary(folder).get("qs_star")
        diff = {c: np.interp(z, p["z"], p[c]) - mean[c] for c in ("phi", "u_p")}
        outside = (z < p["z"].min()) | (z > p["z"].max())
        if (outside & moving).any():
            print(f"  ({name}: {int((outside & moving).sum())} moving cells outside its column, held at its end values)")
        print(f"| {name} | {v:.4g} | {v / qm - 1:+.1%} | {rms(diff['phi']):.4f} | {rms(diff['u_p']):.4f} |")

    # the measure of `saltus compare`'s precision.csv (moving_rms_*): against the first
    # seed, over its own moving rows
    ref = seeds[0]
    grains = ref["phi"] > args.phi_min
    top = np.nanmax(np.where(grains, ref["u_p"], np.nan))
    mask = grains & (ref["u_p"] > args.moving * top)
    print(f"\nagainst {args.dem[0]} alone, over its {int(mask.sum())} moving rows (precision.csv's moving_rms_phi, "
          f"moving_rms_u_p):")
    others = [(d, s) for d, s in zip(args.dem[1:], seeds[1:])]
    others += [(spec.partition("=")[0], load(spec.partition("=")[2])) for spec in args.run]
    for name, p in others:
        d = {c: np.interp(z[mask], p["z"], p[c]) - ref[c][mask] for c in ("phi", "u_p")}
        print(f"| {name} | {math.sqrt(float(np.mean(d['phi'] ** 2))):.4f} | {math.sqrt(float(np.mean(d['u_p'] ** 2))):.4f} |")


if __name__ == "__main__":
    main()
