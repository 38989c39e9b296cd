#!/usr/bin/env python3
"""Coverage of single DEM answers to a requested error against a reference rate.

    python3 docs/figures/answer_coverage.py DIR REF REF_SE

DIR holds run folders `single_s<seed>/` (each `saltus run ... --out DIR/single_s<seed>`);
REF is the reference qs* (e.g. the equilibrium seed mean) and REF_SE its standard error.
Prints the answers' mean and scatter, the mean reported error, the flow and CPU per
answer, and how many intervals answer +- k sqrt(se^2 + REF_SE^2) (and answer +- k se)
hold REF at k = 1 and 2; then the rms of (answer - mean of the answers) / se, the check
of the errors about the answers' own mean. Python standard library only.
"""

import csv
import glob
import json
import math
import statistics
import sys


def answer(summary_path):
    """(qs*, its error, flow s, CPU s, ending, inefficiency s) of one run folder."""
    with open(summary_path) as f:
        d = json.load(f)
    with open(summary_path.replace("summary.json", "timeseries.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    scale = float(last["qs"]) / float(last["qs_star"])
    se = d.get("qs_window_stderr")
    return (d["qs_window"] / scale, (se if se is not None else math.nan) / scale, d["sim_time_s"],
            d["cpu_time_s"], d["ending"], d.get("qs_window_inefficiency_s"))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    folder, ref, ref_se = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    rows = [answer(p) for p in sorted(glob.glob(f"{folder}/single_s*/summary.json"))]
    if len(rows) < 2:
        sys.exit(f"{folder}: fewer than two answers (single_s*/summary.json)")
    q = [r[0] for r in rows]
    e = [r[1] for r in rows]
    mean, sd = statistics.mean(q), statistics.stdev(q)
    endings = {x: sum(r[4] == x for r in rows) for x in sorted({r[4] for r in rows})}
    print(f"answers {len(rows)}, endings {endings}")
    print(f"qs* mean {mean:.4f}, sd {sd:.4f} ({100 * sd / mean:.2f} %), mean reported error "
          f"{statistics.mean(e):.4f} ({100 * statistics.mean(e) / mean:.2f} %)")
    for i, name in ((2, "flow s"), (3, "CPU s")):
        v = [r[i] for r in rows]
        print(f"{name}: {min(v):.1f}-{max(v):.1f}, median {statistics.median(v):.1f}")
    for k in (1, 2):
        held = sum(abs(a - ref) <= k * math.hypot(s, ref_se) for a, s in zip(q, e))
        alone = sum(abs(a - ref) <= k * s for a, s in zip(q, e))
        print(f"{k}-sigma: {held} of {len(q)} hold {ref} (with its error), {alone} without it")
    within = sum(abs(a / ref - 1) <= 0.02 for a in q)
    print(f"within 2 % of {ref}: {within} of {len(q)}; mean against it "
          f"{100 * (mean / ref - 1):+.2f} % +- {100 * sd / math.sqrt(len(q)) / ref:.2f} %")
    z = [(a - mean) / s for a, s in zip(q, e)]
    print(f"about the answers' mean: rms z {math.sqrt(sum(x * x for x in z) / (len(z) - 1)):.2f}, "
          f"{sum(abs(x) <= 1 for x in z)} / {sum(abs(x) <= 2 for x in z)} within 1 / 2 errors")


if __name__ == "__main__":
    main()
