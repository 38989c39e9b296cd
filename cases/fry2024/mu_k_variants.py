"""mu(K) and phi(K) of a DEM run's profiles.csv against Fry's mu_k (eqs 36-38, global fit),
three ways: as written (slices, total stress, = `saltus diagnose`), contact stress only, and
re-weighted with Fry's Gaussian of h_g = d (eq 11) instead of the d/10 slices.
usage: python3 mu_k_variants.py OUT_DIR [h_g/d (default 1)] [K_min (default 0; Fry: 1e-5)]
The constants are those of cases/fry2024/couette_bedload.toml and the mu_k defaults."""
import csv, math, sys

out = sys.argv[1]
hg_d = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
kmin = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
d, rho_p, eta_f = 1e-3, 2500.0, 1000.0 * 9.929275e-5
phi_c, b, mu1, mu2, sk0, alpha = 0.615, 0.7, 0.23, 0.75, 0.18, 0.635

rows = list(csv.DictReader(open(f"{out}/profiles.csv")))
col = lambda k: [float(r[k]) if r[k] not in ("", None) else float("nan") for r in rows]
z, phi, up = col("z"), col("phi"), col("u_p")
tau, pp, tauc, ppc = col("tau_p"), col("p_p"), col("tau_p_contact"), col("p_p_contact")
n = len(z)
dz = z[1] - z[0]

def nz(x):
    return 0.0 if math.isnan(x) else x

def gdot(u):
    g = [float("nan")] * n
    for c in range(n):
        lo, hi = max(c - 1, 0), min(c + 1, n - 1)
        if not (math.isnan(u[lo]) or math.isnan(u[hi])) and hi > lo:
            g[c] = (u[hi] - u[lo]) / ((hi - lo) * dz)
    return g

def compare(label, phi, g, t, p, keep=lambda c: True):
    cells = []
    for c in range(n):
        if not (phi[c] > 0.1 and p[c] > 0 and g[c] == g[c] and g[c] != 0 and t[c] == t[c] and keep(c)):
            continue
        s = abs(g[c])
        i = s * d / math.sqrt(p[c] / rho_p)
        j = eta_f * s / p[c]
        k = j + alpha * i * i
        if k <= kmin:
            continue
        cells.append((k, t[c] / p[c], mu1 + (mu2 - mu1) / (1 + sk0 / math.sqrt(k)), phi[c], phi_c / (1 + b * math.sqrt(k)), z[c]))
    def rel(m, pr):
        rms = math.sqrt(sum((a - b) ** 2 for a, b in zip(m, pr)) / len(m))
        sc = math.sqrt(sum(a * a for a in m) / len(m))
        bias = sum(b - a for a, b in zip(m, pr)) / len(m) / sc
        return rms, rms / sc, bias
    mu = rel([c[1] for c in cells], [c[2] for c in cells])
    ph = rel([c[3] for c in cells], [c[4] for c in cells])
    print(f"{label}: {len(cells)} cells; mu(K) RMS {mu[0]:.3f} rel {mu[1]:.3f} bias {mu[2]:+.3f}; phi(K) RMS {ph[0]:.3f} rel {ph[1]:.3f} bias {ph[2]:+.3f}")
    print("   K decade   cells  mu meas  mu eq38  phi meas  phi eq37")
    for e in range(-7, 3):
        sel = sorted([c for c in cells if 10 ** e <= c[0] < 10 ** (e + 1)])
        if not sel:
            continue
        med = lambda i: sorted(c[i] for c in sel)[len(sel) // 2]
        print(f"   1e{e:+d}-1e{e+1:+d} {len(sel):5d}  {med(1):.3f}    {med(2):.3f}    {med(3):.3f}     {med(4):.3f}")
    return cells

# 1. as diagnose: slices, total stress
compare("slices, total stress (diagnose)", phi, gdot(up), tau, pp)
# 2. contact only
compare("slices, contact stress only", phi, gdot(up), tauc, ppc)
# moving layer only (Fry's exclusion of the static zone: phi < 0.601 and K > 1e-5)
compare("slices, total, moving layer (phi < 0.601)", phi, gdot(up), tau, pp, keep=lambda c: phi[c] < 0.601)
# 3. Gaussian of h_g = hg_d d (Fry eq 11), normalised over the column
hg = hg_d * d
top = z[-1] + dz / 2
def smooth(q):
    s = []
    for c in range(n):
        w = [math.exp(-((z[c] - z[k]) / hg) ** 2) for k in range(n)]
        s.append(sum(wk * nz(q[k]) for k, wk in enumerate(w)) / sum(w))
    return s
phis = smooth(phi)
flux = smooth([nz(a) * nz(b) for a, b in zip(phi, up)])
ups = [f / p if p > 1e-12 else float("nan") for f, p in zip(flux, phis)]
compare(f"Gaussian h_g = {hg_d} d, total stress", phis, gdot(ups), smooth(tau), smooth(pp))
compare(f"Gaussian h_g = {hg_d} d, total, moving layer (phi < 0.601)", phis, gdot(ups), smooth(tau), smooth(pp), keep=lambda c: phis[c] < 0.601)
