"""The posterior of calibrate_couette.toml's four constants (mu_1, phi_c, b of mu(K) and
phi(K), Fry et al. 2024 eqs 37-38, and beta of eq 51) by MCMC, beside the calibration's
Laplace and profile-likelihood errors (docs/calibration.md).

usage: python posterior_couette.py [OUT_DIR (default out/fry2024_couette_posterior)]
       [WALKERS (default 24)] [STEPS (default 1200)]
Needs the saltus package and emcee (pip install ./python emcee)."""
import sys
from pathlib import Path

import saltus

here = Path(__file__).resolve().parent
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/fry2024_couette_posterior")
walkers = int(sys.argv[2]) if len(sys.argv) > 2 else 24
steps = int(sys.argv[3]) if len(sys.argv) > 3 else 1200
file = here / "calibrate_couette.toml"

cal = saltus.calibrate(file, out=out / "calibration")
post = saltus.posterior(file, cal, walkers=walkers, steps=steps, burn=steps // 4, seed=1, out=out)
profile = {p["key"]: p["stderr_profile"] for p in cal.parameters}
print(f"{'constant':28} {'optimum':>9} {'Laplace':>9} {'profile -/+':>19} {'MCMC mean':>10} {'MCMC sd':>9} {'16-84 %':>19} {'tau':>6}")
for row in post.table():
    lo, hi = profile[row["key"]]
    print(
        f"{row['key']:28} {row['optimum']:9.4f} {row['laplace_sd']:9.4f} {lo:9.4f}/{hi:<9.4f} "
        f"{row['mean']:10.4f} {row['sd']:9.4f} {row['p16']:9.4f}-{row['p84']:<9.4f} {row['autocorrelation']:6.1f}"
    )
print("correlation (MCMC):")
print(post.correlation.round(3))
print("correlation (Laplace):")
print(post.laplace_correlation.round(3))
print(
    f"{post.walkers} walkers x {post.steps} steps ({post.burn} burnt), acceptance {post.acceptance:.3f}, "
    f"{post.runs} model runs, {post.wall_time_s:.1f} s wall; chi2 {cal.chi2:.4f} on {cal.dof:.1f} dof"
)
