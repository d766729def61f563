# method: recursion that tries the landmarks nearest in d² first, closed-form χ² distribution
import math

import numpy as np


def _cdf_even(x, dof):
    h = x / 2
    return 1 - math.exp(-h) * sum(h**i / math.factorial(i) for i in range(dof // 2))


def jcbb(mu, P, z, R, confidence):
    mu = np.asarray(mu, dtype=float)
    P = np.asarray(P, dtype=float)
    R = np.asarray(R, dtype=float)
    zs = np.asarray(z, dtype=float).reshape(-1, 2)
    m, N = len(zs), (mu.size - 3) // 2

    def obs(j):
        dx, dy = mu[3 + 2 * j] - mu[0], mu[4 + 2 * j] - mu[1]
        q = dx * dx + dy * dy
        r = math.sqrt(q)
        H = np.zeros((2, mu.size))
        H[0, 0], H[0, 1] = -dx / r, -dy / r
        H[1, 0], H[1, 1], H[1, 2] = dy / q, -dx / q, -1.0
        H[0, 3 + 2 * j], H[0, 4 + 2 * j] = dx / r, dy / r
        H[1, 3 + 2 * j], H[1, 4 + 2 * j] = -dy / q, dx / q
        return r, math.atan2(dy, dx) - mu[2], H

    models = [obs(j) for j in range(N)]

    def d2(pairs):
        if not pairs:
            return 0.0
        nu = np.zeros(2 * len(pairs))
        H = np.zeros((2 * len(pairs), mu.size))
        for k, (i, j) in enumerate(pairs):
            r, b, Hj = models[j]
            e = zs[i, 1] - b
            while e > math.pi:
                e -= 2 * math.pi
            while e <= -math.pi:
                e += 2 * math.pi
            nu[2 * k], nu[2 * k + 1] = zs[i, 0] - r, e
            H[2 * k : 2 * k + 2] = Hj
        S = H @ P @ H.T + np.kron(np.eye(len(pairs)), R)
        L = np.linalg.cholesky(S)
        w = np.linalg.solve(L, nu)
        return float(w @ w)

    single = {(i, j): d2([(i, j)]) for i in range(m) for j in range(N)}
    best = [0, 0.0, []]

    def go(i, pairs):
        if i == m:
            value = d2(pairs)
            if len(pairs) > best[0] or (len(pairs) == best[0] and value < best[1]):
                best[:] = [len(pairs), value, list(pairs)]
            return
        used = {j for _, j in pairs}
        for j in sorted(range(N), key=lambda j: single[(i, j)]):
            if j in used or _cdf_even(single[(i, j)], 2) >= confidence:
                continue
            trial = pairs + [(i, j)]
            if _cdf_even(d2(trial), 2 * len(trial)) < confidence:
                go(i + 1, trial)
        if len(pairs) + m - i - 1 >= best[0]:
            go(i + 1, pairs)

    go(0, [])
    out = [-1] * m
    for i, j in best[2]:
        out[i] = j
    return out
