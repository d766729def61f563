# method: branch and bound with an explicit stack instead of recursion, quantiles from scipy
import math

import numpy as np
from scipy.stats import chi2


def jcbb(mu, P, z, R, confidence):
    mu = np.asarray(mu, dtype=float)
    P = np.asarray(P, dtype=float)
    R = np.asarray(R, dtype=float)
    z = [tuple(map(float, zi)) for zi in z]
    m, N = len(z), (len(mu) - 3) // 2
    pred = []
    for j in range(N):
        dx, dy = mu[3 + 2 * j] - mu[0], mu[4 + 2 * j] - mu[1]
        q = dx * dx + dy * dy
        r = math.sqrt(q)
        H = np.zeros((2, len(mu)))
        H[0, [0, 1, 3 + 2 * j, 4 + 2 * j]] = [-dx / r, -dy / r, dx / r, dy / r]
        H[1, [0, 1, 2, 3 + 2 * j, 4 + 2 * j]] = [dy / q, -dx / q, -1.0, -dy / q, dx / q]
        pred.append((r, math.atan2(dy, dx) - mu[2], H))

    def joint(pairs):
        if not pairs:
            return 0.0
        nu = []
        H = []
        for i, j in pairs:
            r, b, Hj = pred[j]
            nu += [z[i][0] - r, math.remainder(z[i][1] - b, 2 * math.pi)]
            H.append(Hj)
        H = np.vstack(H)
        S = H @ P @ H.T
        for k in range(len(pairs)):
            S[2 * k : 2 * k + 2, 2 * k : 2 * k + 2] += R
        nu = np.array(nu)
        return float(nu @ np.linalg.solve(S, nu))

    gates = [0.0] + [chi2.ppf(confidence, 2 * k) for k in range(1, m + 1)]
    best_pairs, best_k, best_d2 = [], 0, 0.0
    stack = [(0, [])]  # (next measurement, pairs so far)
    while stack:
        i, pairs = stack.pop()
        if i == m:
            d2 = joint(pairs)
            if len(pairs) > best_k or (len(pairs) == best_k and d2 < best_d2):
                best_pairs, best_k, best_d2 = pairs, len(pairs), d2
            continue
        children = []
        used = {j for _, j in pairs}
        for j in range(N):
            if j in used or joint([(i, j)]) >= gates[1]:
                continue
            trial = pairs + [(i, j)]
            if joint(trial) < gates[len(trial)]:
                children.append((i + 1, trial))
        if len(pairs) + (m - i - 1) >= best_k:
            children.append((i + 1, pairs))
        stack.extend(reversed(children))
    out = [-1] * m
    for i, j in best_pairs:
        out[i] = j
    return out
