#!/usr/bin/python3
"""The 3D uniaxial check: a box pulled in y (grips of one row inside, holding y only;
lateral faces free), static. In the middle rows: the axial stretch lambda (mean row
increment), the lateral stretch (least-squares slope of u_x over x and of u_z over z, + 1)
and the nominal stress (top grip's reaction / reference section) against the
compressible 3D Gent law's uniaxial response at that lambda:
  Psi = -(mu Jm/2) ln(1 - (I1bar - 3)/Jm) + (1/D)((J^2 - 1)/2 - ln J),
  F = diag(l, lambda, l), I1bar = J^{-2/3} (lambda^2 + 2 l^2), J = lambda l^2,
  l from dPsi/dl = 0 (Newton), P = dPsi/dlambda.
Usage: check_uniaxial_3d.py OUTPUT_DIR LOG mu Jm bulk_ratio area tol_stress tol_lateral tol_alternation"""
import csv, math, re, sys

out, log = sys.argv[1], sys.argv[2]
mu, Jm, ratio, area = (float(v) for v in sys.argv[3:7])
tol_p, tol_l, tol_alt = (float(v) for v in sys.argv[7:10])
D = 2.0 / (ratio * mu)


def psi(lam, l):
    J = lam * l * l
    I1bar = (lam * lam + 2 * l * l) / J ** (2.0 / 3.0)
    return -0.5 * mu * Jm * math.log1p(-(I1bar - 3.0) / Jm) + ((J * J - 1.0) / 2.0 - math.log(J)) / D


def d(f, x, h=1e-6):
    return (f(x + h) - f(x - h)) / (2 * h)


def law(lam):
    l = 1.0
    for _ in range(50):  # Newton on dPsi/dl = 0, derivatives by central differences
        g = d(lambda s: psi(lam, s), l)
        k = d(lambda s: d(lambda t: psi(lam, t), s, 1e-5), l, 1e-5)
        l -= g / k
        if abs(g) < 1e-10 * mu: break
    return l, d(lambda s: psi(s, l), lam)


rows = list(csv.DictReader(open(out + "/final_state.csv")))
by_row = {}  # reference y (rounded) -> the u_y of that row's points
for r in rows:
    by_row.setdefault(round(float(r["y_m"]), 9), []).append(float(r["uy_m"]))
ys = sorted(by_row)
n = len(ys)
mean_uy = [sum(by_row[y]) / len(by_row[y]) for y in ys]
inc = [(mean_uy[k + 1] - mean_uy[k]) / (ys[k + 1] - ys[k]) for k in range(n - 1)]
mid = inc[n // 2 - 3 : n // 2 + 2]  # the 5 increments around the middle
lam = 1.0 + sum(mid) / len(mid)
alternation = (max(mid) - min(mid)) / (sum(mid) / len(mid))
# the rows within one spacing of the middle (2 rows of an even count)
mid_rows = [r for r in rows if abs(float(r["y_m"]) - 0.5 * (ys[0] + ys[-1])) < 1.01 * (ys[1] - ys[0])]


def slope(c):
    xs = [float(r[c + "_m"]) for r in mid_rows]
    us = [float(r["u" + c + "_m"]) for r in mid_rows]
    mx, mu_ = sum(xs) / len(xs), sum(us) / len(us)
    return sum((a - mx) * (b - mu_) for a, b in zip(xs, us)) / sum((a - mx) ** 2 for a in xs)


lat = 1.0 + 0.5 * (slope("x") + slope("z"))
m = re.search(r"load set top +reaction x, y, z = \S+, (\S+),", open(log).read())
P = float(m.group(1)) / area
l_law, P_law = law(lam)
err_p, err_l = P / P_law - 1.0, (lat - 1.0) / (l_law - 1.0) - 1.0
print(f"middle: lambda = {lam:.5f}, (max - min) / mean of the row increments: {alternation:.4f} (tolerance {tol_alt})")
print(f"nominal stress {P:.2f} Pa, law {P_law:.2f} Pa: {100 * err_p:+.2f} % (tolerance {100 * tol_p:.1f} %)")
print(f"lateral stretch {lat:.5f}, law {l_law:.5f}: contraction {100 * err_l:+.2f} % of the law's (tolerance {100 * tol_l:.1f} %)")
ok = abs(err_p) <= tol_p and abs(err_l) <= tol_l and alternation <= tol_alt
print("uniaxial check:", "passed" if ok else "FAILED")
sys.exit(0 if ok else 1)
