#!/usr/bin/python3
"""The point form's volumetric energy (docs/method.md section 8) linearised about the
reference state, on small lattices, to find which modes it leaves soft at a gel's K and
to try stabilisations of the spread of the bonds' dilatations (docs/notes/volumetric-odd-even.md).

Linearised, F_iq = I + H_iq with H_iq = sum_{k in B_iq} (u_k - u_i) (x) g_k (eq 9,
g_k = K_iq^{-1} xi_k V_k), the Gent law is mu |dev sym H|^2 (3D deviator, also in plane
strain) + K/2 (tr H)^2, and the energy of point i is, with w_q = omega_i V_q,
  V_i [ sum_q w_q (mu |dev sym H_iq|^2 + kappa/2 (th_q - thbar)^2) + K/2 thbar^2 ],
th_q = tr H_iq, thbar = sum_q w_q th_q (kappa = K: the bond form). Stabilisation
"smooth": kappa/2 times the spread about thbar plus kappa_r/2 times the part of th_q
that no quadratic field explains (residual of the w-weighted least-squares fit of th_q on
{1, phi^abc_q}, phi^abc_q = sum_k xi_a xi_b g_k,c: the bond's dilatation of a quadratic u).

Needs numpy. Usage:
  volumetric_modes.py box  DIM NX NY NZ form kappa_mu kappa_r_mu K_mu   # uniaxial box, linear
  volumetric_modes.py eig  DIM N form kappa_mu kappa_r_mu K_mu          # lowest modes of a free box
  volumetric_modes.py slab 2 H form kappa_mu kappa_r_mu K_mu           # the plane-strain slab, spacing H mm
  volumetric_modes.py lock DIM N form kappa_mu kappa_r_mu K_mu          # isochoric field's interior energy
form: bond | point | smooth | pair | pairwhole | pair2 | pairbond. pair: kappa_r/2 on the
spread of the pairs' dilatations (th_iq + th_qi)/2 about thbar_i; pairwhole: the same on
pairs of whole families only; pair2: about the pair's mean (thbar_i + thbar_q)/2;
pairbond: the bond form with the pair's dilatation. Numbers: docs/notes/volumetric-odd-even.md."""
import itertools, sys
import numpy as np

MU, DX, FACTOR = 1.0, 1.0, 3.015


def lattice(shape):
    axes = [np.arange(n) + 0.5 for n in shape]
    return np.array(list(itertools.product(*axes)), dtype=float) * DX


def stiffness(X, form, kappa, kappa_r, K, only=None):
    n, D = X.shape
    rows = {}  # (i, q) -> (dofs, row of th_iq): the pair forms' second pass
    V = DX ** D
    delta = FACTOR * DX
    Kg = np.zeros((n * D, n * D))
    d2 = ((X[:, None, :] - X[None, :, :]) ** 2).sum(-1)
    pairs = [(a, b) for a in range(D) for b in range(a, D)]
    for i in range(n):
        fam = np.where((d2[i] <= delta * delta) & (np.arange(n) != i))[0]
        if only is not None and not only[i]: continue
        xi = X[fam] - X[i]
        nb, nm = len(fam), len(fam)
        G = np.zeros((nb, nm, D))
        phi = np.zeros((nb, len(pairs) * D))
        for q in range(nb):
            members = d2[fam[q], fam] <= delta * delta
            Kq = (xi[members, :, None] * xi[members, None, :]).sum(0) * V
            g = np.linalg.solve(Kq, xi[members].T).T * V
            G[q, members] = g
            xm = xi[members]
            phi[q] = [(xm[:, a] * xm[:, b] * g[:, c]).sum() for (a, b) in pairs for c in range(D)]
        w = np.full(nb, 1.0 / nb)
        Gf = G.reshape(nb, nm * D)
        T3 = Gf.T @ (w[:, None] * Gf)  # sum_q w (trH-row)(...): indices (m a, n b) -> G_qma G_qnb
        T3r = T3.reshape(nm, D, nm, D)
        T2 = T3r.transpose(0, 3, 2, 1).reshape(nm * D, nm * D)  # G_qmb G_qna
        T1 = np.einsum('mana->mn', T3r)
        tvec = G.reshape(nb, nm, D)  # th_q = sum_m U_m . G_qm
        tf = tvec.reshape(nb, nm * D)
        tbar = w @ tf
        spread = tf.T @ (w[:, None] * tf) - np.outer(tbar, tbar)
        A = MU * (0.5 * (np.kron(T1, np.eye(D)) + T2) - T3 / 3.0)
        if form == "pairbond":
            pass  # all volumetric energy in the second pass
        elif form == "bond":
            A += 0.5 * K * (tf.T @ (w[:, None] * tf))
        else:
            A += 0.5 * kappa * spread + 0.5 * K * np.outer(tbar, tbar)
            if form == "smooth" and kappa_r:
                B = np.hstack([np.ones((nb, 1)), phi])
                Bw = B * np.sqrt(w)[:, None]
                Qm, _ = np.linalg.qr(Bw)
                R = np.diag(np.sqrt(w)) @ tf  # sqrt(w) th
                Rr = R - Qm @ (Qm.T @ R)      # residual, weighted
                A += 0.5 * kappa_r * (Rr.T @ Rr)
        # U_m = u_m - u_i
        dofs = np.concatenate([[D * i + c for c in range(D)]] + [[D * m + c for c in range(D)] for m in fam])
        P = np.zeros((nm * D, (nm + 1) * D))
        for m in range(nm):
            for c in range(D):
                P[m * D + c, (m + 1) * D + c] = 1.0
                P[m * D + c, c] = -1.0
        Kl = 2.0 * V * (P.T @ A @ P)
        Kg[np.ix_(dofs, dofs)] += Kl
        if form in ("pair", "pair2", "pairbond", "pairwhole"):
            full = tf @ P  # th_q over the local dofs
            for q in range(nb): rows[(i, fam[q])] = (dofs, full[q], w[q], full.T @ w if q == 0 else None)
    first, bonds_of = {}, {}
    for (a, q) in rows:
        first.setdefault(a, q)
        bonds_of.setdefault(a, []).append(q)
    whole = max((len(v) for v in bonds_of.values()), default=0)
    if form in ("pair", "pair2", "pairbond", "pairwhole"):
        # th^pair_iq = (th_iq + th_qi) / 2: the divergence at the bond's midpoint to second
        # order for a smooth field (B_qi is B_iq reflected through the midpoint).
        # pair: kappa_r/2 sum_q w_q (th^pair_iq - thbar_i)^2 added to the point form;
        # pairbond: K/2 sum_q w_q (th^pair_iq)^2 in place of every volumetric term.
        for i in range(n):
            if only is not None and not only[i]: continue
            fam = bonds_of[i]
            dofs_i, _, _, tbar = rows[(i, first[i])]
            for q in fam:
                if (q, i) not in rows: continue  # q outside the mask
                if form == "pairwhole" and not (len(bonds_of[i]) == whole and len(bonds_of[q]) == whole):
                    continue  # pairwhole: only pairs of whole families, where B_qi reflects B_iq
                di, ri, wq, _ = rows[(i, q)]
                dq, rq, _, _ = rows[(q, i)]
                terms = [(di, 0.5 * ri), (dq, 0.5 * rq)]
                if form in ("pair", "pairwhole"):
                    terms.append((dofs_i, -tbar))
                    c = kappa_r
                elif form == "pair2":  # about the pair's mean dilatation (thbar_i + thbar_q) / 2
                    dofs_q, _, _, tbar_q = rows[(q, first[q])]
                    terms += [(dofs_i, -0.5 * tbar), (dofs_q, -0.5 * tbar_q)]
                    c = kappa_r
                else:
                    c = K
                idx = np.unique(np.concatenate([d for d, _ in terms]))
                r = np.zeros(len(idx))
                for d, v in terms: np.add.at(r, np.searchsorted(idx, d), v)
                Kg[np.ix_(idx, idx)] += V * wq * c * np.outer(r, r)
    return Kg


def box(D, shape, form, kappa, kappa_r, K, strain=0.01):
    X = lattice(shape)
    n = len(X)
    Kg = stiffness(X, form, kappa, kappa_r, K)
    yy = X[:, 1]
    lo, hi = yy.min(), yy.max()
    fixed = [D * i + 1 for i in range(n) if yy[i] in (lo, hi)]
    u = np.zeros(n * D)
    for i in range(n):
        if yy[i] == hi: u[D * i + 1] = strain * shape[1] * DX
    free = np.setdiff1d(np.arange(n * D), fixed)
    Kff = Kg[np.ix_(free, free)] + 1e-10 * np.abs(Kg).max() * np.eye(len(free))  # the rigid x, z modes
    u[free] = np.linalg.solve(Kff, -Kg[np.ix_(free, fixed)] @ u[fixed])
    rows = sorted(set(yy))
    mean = np.array([u[D * np.where(yy == r)[0] + 1].mean() for r in rows])
    inc = np.diff(mean) / DX
    nr = len(rows)
    mid = inc[nr // 2 - 3: nr // 2 + 2]
    print("increments / strain:", " ".join(f"{v / strain:.3f}" for v in inc))
    print(f"alternation (max - min) / mean of the 5 middle increments: {100 * (mid.max() - mid.min()) / mid.mean():.2f} %")
    top = [D * i + 1 for i in range(n) if yy[i] == hi]
    reaction = (Kg[top] @ u).sum() / (shape[0] * (shape[2] if D == 3 else 1) * DX ** (D - 1))
    lam = K - 2 * MU / 3  # the law's uniaxial modulus (plane strain: lateral x free, z held)
    E = 9 * K * MU / (3 * K + MU) if D == 3 else 4 * MU * (lam + MU) / (lam + 2 * MU)
    print(f"nominal stress over the law's at the middle strain: {reaction / (E * mid.mean()) - 1:+.4f}")


def slab(h, form, kappa, kappa_r, K, strain=0.01):
    """examples/slab_plane_strain.yaml linearised, in units of mm: 10 x 20, hole r = 2.5 at
    (5, 10), rigid grips of 4 rows outside holding x and y; reaction over the law's at K."""
    global DX
    DX = h
    X = lattice([int(round(10 / h)), int(round(20 / h) + 8)])
    X[:, 1] -= 4 * h
    X = X[np.hypot(X[:, 0] - 5, X[:, 1] - 10) > 2.5]
    n, D = len(X), 2
    Kg = stiffness(X, form, kappa, kappa_r, K)
    top, bottom = X[:, 1] > 20, X[:, 1] < 0
    u = np.zeros(n * D)
    u[2 * np.where(top)[0] + 1] = strain * 20
    fixed = np.concatenate([[2 * i, 2 * i + 1] for i in np.where(top | bottom)[0]])
    free = np.setdiff1d(np.arange(n * D), fixed)
    u[free] = np.linalg.solve(Kg[np.ix_(free, free)], -Kg[np.ix_(free, fixed)] @ u[fixed])
    reaction = (Kg[2 * np.where(top)[0] + 1] @ u).sum()
    probes = {"side": (h / 2, 10 - h / 2), "ligament": (2.5 - h / 2, 10 - h / 2), "crown": (5 - h / 2, 12.5 + h / 2)}
    out = [f"reaction {reaction / (MU * strain):.5f} mu strain mm"]
    for name, (px, py) in probes.items():
        i = np.argmin(np.hypot(X[:, 0] - px, X[:, 1] - py))
        out.append(f"{name} ({X[i, 0]:.2f}, {X[i, 1]:.2f}) u = ({u[2 * i] / strain:+.4f}, {u[2 * i + 1] / strain:+.4f}) strain mm")
    print("; ".join(out))


def lowest(D, N, form, kappa, kappa_r, K, count=12):
    X = lattice([N] * D)
    Kg = stiffness(X, form, kappa, kappa_r, K)
    vals, vecs = np.linalg.eigh(Kg)
    depth = np.min(np.minimum(X, N * DX - X), axis=1)
    stagger = (-1.0) ** np.floor(X / DX).sum(1)
    nrig = 3 if D == 2 else 6
    print("eigenvalue / mu | share of |v|^2 at depth < 1.5 dx | odd-even share (u . (-1)^(i+j+k))")
    for k in range(nrig, nrig + count):
        v = vecs[:, k].reshape(-1, D)
        e = (v ** 2).sum(1)
        surf = e[depth < 1.5 * DX].sum() / e.sum()
        oe = sum((v[:, c] * stagger).sum() ** 2 for c in range(D)) / e.sum() / len(X)
        rowalt = sum(((v[:, c] * (-1.0) ** np.floor(X[:, c] / DX)).sum()) ** 2 for c in range(D)) / e.sum() / len(X)
        print(f"{vals[k] / MU:10.4f}  surface {surf:.2f}  checkerboard {oe:.2f}  row-alternation {rowalt:.2f}")


def lock(D, N, form, kappa, kappa_r, K, e=1e-3):
    X = lattice([N] * D)
    L = N * DX
    u = np.zeros_like(X)
    if D == 2:
        u[:, 0], u[:, 1] = e * X[:, 0] ** 2 / L, -2 * e * X[:, 0] * X[:, 1] / L
    else:
        u[:, 0] = e * (X[:, 0] ** 2 + X[:, 1] * X[:, 2]) / L
        u[:, 1] = e * (-2 * X[:, 0] * X[:, 1] + X[:, 2] ** 2) / L
    depth = np.min(np.minimum(X, L - X), axis=1)
    only = depth >= 2 * FACTOR * DX + DX  # whole families, and their neighbours' too
    Kg = stiffness(X, form, kappa, kappa_r, K, only)
    ref = stiffness(X, "point", 0.0, 0.0, 0.0, only)
    uf = u.ravel()
    print(f"isochoric quadratic field: energy / (energy at kappa = K = 0): {(uf @ Kg @ uf) / (uf @ ref @ uf):.4f}")


if __name__ == "__main__":
    what, D = sys.argv[1], int(sys.argv[2])
    if what == "box":
        shape = [int(v) for v in sys.argv[3:3 + D]]
        form, k, kr, K = sys.argv[3 + D], *(float(v) * MU for v in sys.argv[4 + D:7 + D])
        box(D, shape, form, k, kr, K)
    elif what == "slab":
        h = float(sys.argv[3])
        form, k, kr, K = sys.argv[4], *(float(v) * MU for v in sys.argv[5:8])
        slab(h, form, k, kr, K)
    else:
        N = int(sys.argv[3])
        form, k, kr, K = sys.argv[4], *(float(v) * MU for v in sys.argv[5:8])
        (lowest if what == "eig" else lock)(D, N, form, k, kr, K)
