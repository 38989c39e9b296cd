#!/usr/bin/env python3
"""Independent check of the k-omega channel (docs/notes/k_omega_channel.md).

Steady solution of the low-Re k-omega of Cheng et al. table 1 (Wilcox's low-Re functions,
eqs 21-29 with phi = 0) for the half channel at Re_tau = 587.19 in wall units (nu = u* = 1),
written independently of the Rust solver: vertex-centred grid stretched geometrically from
the wall, the momentum integrated exactly from the linear total stress
(1 + nu_t+) dU+/dy+ = 1 - y+/Re_tau (so the shear in the production is exact at the nodes),
k and omega by pseudo-time implicit steps (Thomas algorithm), k = 0 at the wall node and
omega = 6/(beta_w y+^2) at every node with y+ <= 2.5 (Wilcox's near-wall solution).
Pure Python, no dependencies; compares with shared/data/mkm1999_chan590.

usage: python3 k_omega_channel_reference.py [nodes] [first y+] [--b072] [--highre]
  --b072   beta_w = 0.072 (C_2omega) in the wall value instead of Cheng's 0.075 (eq 31)
  --highre damping functions off (alpha* = 1, C_mu* = C_mu, C_1w* = C_1w)
"""
import math, sys
RE = 587.19
a0, as0, Rk, Rw, Rb, cmu, sig, c1, beta = 1/9, 0.024, 6.0, 2.95, 8.0, 0.09, 2.0, 0.52, 0.072
lowre = '--highre' not in sys.argv
wallb = 0.072 if '--b072' in sys.argv else 0.075
N = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 200
y1 = float(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[2][0].isdigit() else 0.05
# geometric ratio so that y_N = RE
lo, hi = 1.0000001, 1.5
for _ in range(200):
    r = 0.5*(lo+hi)
    s = y1*(r**N-1)/(r-1)
    if s > RE: hi = r
    else: lo = r
y = [0.0]
for i in range(N):
    y.append(y[-1] + y1*r**i)
y[-1] = RE
n = len(y)
def astar(rt):
    if not lowre: return 1.0
    q = rt/Rk; return (as0+q)/(1+q)
def cmus(rt):
    if not lowre: return cmu
    q = (rt/Rb)**4; return cmu*(4/15+q)/(1+q)
def wprod(rt):
    if not lowre: return c1
    q = rt/Rw; return c1*(a0+q)/(1+q)
k = [1.0]*n; w = [max(1.0, 6/(beta*max(yy,1e-3)**2)) for yy in y]; k[0] = 0.0
def thomas(a, b, c, d):
    m = len(d); cp = [0.0]*m; dp = [0.0]*m
    cp[0] = c[0]/b[0]; dp[0] = d[0]/b[0]
    for i in range(1, m):
        den = b[i]-a[i]*cp[i-1]; cp[i] = c[i]/den; dp[i] = (d[i]-a[i]*dp[i-1])/den
    x = [0.0]*m; x[-1] = dp[-1]
    for i in range(m-2, -1, -1): x[i] = dp[i]-cp[i]*x[i+1]
    return x
def nut_of(k, w): return [astar(k[i]/w[i])*k[i]/w[i] for i in range(n)]
dt = 1.0
for it in range(20000):
    nt = nut_of(k, w)
    S = [(1-y[i]/RE)/(1+nt[i]) for i in range(n)]
    # control volumes
    vol = [0.0]*n
    for i in range(n):
        l = y[i]-y[i-1] if i > 0 else 0.0
        rr = y[i+1]-y[i] if i < n-1 else 0.0
        vol[i] = 0.5*(l+rr)
    dk = [1+nt[i]/sig for i in range(n)]
    kold, wold = k[:], w[:]
    for field in ('k', 'w'):
        A = [0.0]*n; B = [0.0]*n; C = [0.0]*n; D = [0.0]*n
        for i in range(n):
            rt = k[i]/w[i]
            if field == 'k':
                src = nt[i]*S[i]**2; snk = cmus(rt)*w[i]; q = k[i]
            else:
                src = wprod(rt)*S[i]**2; snk = beta*w[i]; q = w[i]
            B[i] = vol[i]/dt + snk*vol[i]; D[i] = vol[i]/dt*q + src*vol[i]
        for i in range(n-1):
            c = 0.5*(dk[i]+dk[i+1])/(y[i+1]-y[i])
            B[i] += c; C[i] = -c; B[i+1] += c; A[i+1] = -c
        # Dirichlet rows
        for i in range(n):
            fix = None
            if field == 'k' and i == 0: fix = 0.0
            if field == 'w' and (i == 0 or y[i] <= 2.5):
                fix = 6/(wallb*y[max(i,1)]**2) if i > 0 else 6/(wallb*y[1]**2)*100
            if fix is not None:
                A[i] = 0.0; C[i] = 0.0; B[i] = 1.0; D[i] = fix
        x = thomas(A, B, C, D)
        if field == 'k': k = [max(v, 0.0) for v in x]
        else: w = x
    ch = max(abs(k[i]-kold[i]) for i in range(n))/max(k)
    dt = min(dt*1.2, 1e4)
    if ch < 1e-13 and it > 300: break
nt = nut_of(k, w)
U = [0.0]*n
for i in range(1, n):
    # integrate dU/dy = (1 - y/RE)/(1 + nu_t) with the midpoint value
    ym = 0.5*(y[i]+y[i-1]); ntm = 0.5*(nt[i]+nt[i-1])
    U[i] = U[i-1] + (y[i]-y[i-1])*(1-ym/RE)/(1+ntm)
dns = [l.split() for l in open(__import__('os').path.join(__import__('os').path.dirname(__import__('os').path.abspath(__file__)), '../../../shared/data/mkm1999_chan590/chan590.means')) if not l.startswith('#') and l.strip()]
yp = [float(r[1]) for r in dns]; up = [float(r[2]) for r in dns]
def interp(xs, ys, a):
    for j in range(1, len(xs)):
        if xs[j] >= a: t = (a-xs[j-1])/(xs[j]-xs[j-1]); return ys[j-1]*(1-t)+ys[j]*t
    return ys[-1]
worst = max(abs(interp(y, U, yy)/interp(yp, up, yy)-1) for yy in [30+i for i in range(0, 147)])
ik = max(range(n), key=lambda i: k[i])
print(f"N={N} y1+={y1} lowre={lowre} wall_beta={wallb} iters={it}: U+(10) {interp(y,U,10):.3f} ({interp(yp,up,10):.3f}) U+(30) {interp(y,U,30):.3f} ({interp(yp,up,30):.3f}) U+(100) {interp(y,U,100):.3f} ({interp(yp,up,100):.3f}) centre {U[-1]:.3f} ({up[-1]:.3f}, {100*(U[-1]/up[-1]-1):+.2f}%) worst30-176 {100*worst:.2f}% k+ peak {k[ik]:.3f} at {y[ik]:.1f}; B(y+=100..200) {sum(interp(y,U,yy)-math.log(yy)/0.41 for yy in range(100,201))/101:.3f}")
