# method: recursion that re-predicts every pairing and rebuilds S_H (np.kron) at each node
import math

import numpy as np


def _chi2_below(d2, dof, p):
    """True when d² is below the χ² quantile at p (an even number of degrees of freedom)."""
    x = d2 / 2
    cdf = 1 - math.exp(-x) * sum(x**i / math.factorial(i) for i in range(dof // 2))
    return cdf < p


def _predict(mu, j):
    x, y, th = mu[0], mu[1], mu[2]
    dx, dy = mu[3 + 2 * j] - x, mu[4 + 2 * j] - y
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    h = np.array([r, math.atan2(dy, dx) - th])
    H = np.zeros((2, len(mu)))
    H[:, :3] = [[-dx / r, -dy / r, 0], [dy / q, -dx / q, -1]]
    H[:, 3 + 2 * j : 5 + 2 * j] = [[dx / r, dy / r], [-dy / q, dx / q]]
    return h, H


def jcbb(mu, P, z, R, confidence):
    mu = np.array(mu, dtype=float)
    P = np.array(P, dtype=float)
    R = np.array(R, dtype=float)
    z = np.array(z, dtype=float).reshape(-1, 2)
    m, n_lm = len(z), (len(mu) - 3) // 2

    def d2_of(pairing):
        nus, Hs = [], []
        for i, j in enumerate(pairing):
            if j < 0:
                continue
            h, H = _predict(mu, j)
            nu = z[i] - h
            nu[1] = (nu[1] + math.pi) % (2 * math.pi) - math.pi
            nus.append(nu)
            Hs.append(H)
        if not nus:
            return 0.0
        nu, H = np.concatenate(nus), np.vstack(Hs)
        S = H @ P @ H.T + np.kron(np.eye(len(nus)), R)
        return float(nu @ np.linalg.solve(S, nu))

    def alone(i, j):
        return [j if k == i else -1 for k in range(m)]

    ok = [[_chi2_below(d2_of(alone(i, j)), 2, confidence) for j in range(n_lm)] for i in range(m)]
    best = {"k": 0, "d2": 0.0, "pairing": [-1] * m}

    def search(i, pairing, k):
        if i == m:
            d2 = d2_of(pairing)
            if k > best["k"] or (k == best["k"] and d2 < best["d2"]):
                best.update(k=k, d2=d2, pairing=list(pairing))
            return
        for j in range(n_lm):
            if j in pairing or not ok[i][j]:
                continue
            trial = [*pairing, j]
            if _chi2_below(d2_of(trial + [-1] * (m - i - 1)), 2 * (k + 1), confidence):
                search(i + 1, trial, k + 1)
        if k + (m - i - 1) >= best["k"]:
            search(i + 1, [*pairing, -1], k)

    search(0, [], 0)
    return best["pairing"]
