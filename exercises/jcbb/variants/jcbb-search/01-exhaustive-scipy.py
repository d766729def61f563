# method: every hypothesis listed with itertools.product, gates from scipy.stats.chi2
import itertools
import math

import numpy as np
from scipy.stats import chi2


def jcbb(mu, P, z, R, confidence):
    mu = np.asarray(mu, dtype=float)
    P = np.asarray(P, dtype=float)
    R = np.asarray(R, dtype=float)
    z = np.asarray(z, dtype=float).reshape(-1, 2)
    m, N = len(z), (len(mu) - 3) // 2

    def model(j):
        d = mu[3 + 2 * j : 5 + 2 * j] - mu[:2]
        q = float(d @ d)
        r = math.sqrt(q)
        H = np.zeros((2, len(mu)))
        H[0, :2], H[0, 3 + 2 * j : 5 + 2 * j] = -d / r, d / r
        H[1, :2], H[1, 3 + 2 * j : 5 + 2 * j] = [d[1] / q, -d[0] / q], [-d[1] / q, d[0] / q]
        H[1, 2] = -1.0
        return np.array([r, math.atan2(d[1], d[0]) - mu[2]]), H

    def d2(pairs):
        if not pairs:
            return 0.0
        nus, Hs = [], []
        for i, j in pairs:
            h, H = model(j)
            nu = z[i] - h
            nu[1] = math.atan2(math.sin(nu[1]), math.cos(nu[1]))
            nus.append(nu)
            Hs.append(H)
        H = np.vstack(Hs)
        S = H @ P @ H.T + np.kron(np.eye(len(pairs)), R)
        nu = np.concatenate(nus)
        return float(nu @ np.linalg.inv(S) @ nu)

    gate1 = chi2.ppf(confidence, 2)
    best, best_key = [-1] * m, (0, 0.0)
    for hyp in itertools.product(range(-1, N), repeat=m):
        pairs = [(i, j) for i, j in enumerate(hyp) if j >= 0]
        if len({j for _, j in pairs}) != len(pairs):
            continue
        if any(d2([p]) >= gate1 for p in pairs):
            continue
        value = d2(pairs)
        if pairs and value >= chi2.ppf(confidence, 2 * len(pairs)):
            continue
        key = (len(pairs), value)
        if key[0] > best_key[0] or (key[0] == best_key[0] and key[1] < best_key[1]):
            best, best_key = list(hyp), key
    return best
