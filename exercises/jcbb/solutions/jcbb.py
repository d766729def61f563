import math

import numpy as np


def _chi2_below(d2, dof, p):
    """True when d² is below the χ² quantile at p (an even number of degrees of freedom)."""
    x = d2 / 2
    cdf = 1 - math.exp(-x) * sum(x**i / math.factorial(i) for i in range(dof // 2))
    return cdf < p


def jcbb(mu, P, z, R, confidence):
    mu = np.asarray(mu, dtype=float)
    P = np.asarray(P, dtype=float)
    R = np.asarray(R, dtype=float)
    z = np.asarray(z, dtype=float).reshape(-1, 2)
    m, n_lm = len(z), (len(mu) - 3) // 2

    # every landmark's prediction h_j and Jacobian H_j (2 x n), once
    d = mu[3:].reshape(-1, 2) - mu[:2]
    q = np.einsum("ji,ji->j", d, d)
    r = np.sqrt(q)
    dx, dy = d[:, 0], d[:, 1]
    lm = np.arange(n_lm)
    H = np.zeros((n_lm, 2, len(mu)))
    H[:, 0, 0], H[:, 0, 1] = -dx / r, -dy / r
    H[:, 1, 0], H[:, 1, 1], H[:, 1, 2] = dy / q, -dx / q, -1.0
    H[lm, 0, 3 + 2 * lm], H[lm, 0, 4 + 2 * lm] = dx / r, dy / r
    H[lm, 1, 3 + 2 * lm], H[lm, 1, 4 + 2 * lm] = -dy / q, dx / q
    H = H.reshape(2 * n_lm, -1)
    # the innovation of every (measurement, landmark) pair, bearing wrapped into (-pi, pi]
    nu = z[:, None, :] - np.stack([r, np.arctan2(dy, dx) - mu[2]], axis=1)
    nu[:, :, 1] = np.pi - np.remainder(np.pi - nu[:, :, 1], 2 * np.pi)
    # H P Hᵀ + blockdiag(R, ..., R) over all landmarks: as a hypothesis uses each landmark at
    # most once, its S_H is the rows and columns of its landmarks
    s_all = H @ P @ H.T
    for k in range(n_lm):
        s_all[2 * k : 2 * k + 2, 2 * k : 2 * k + 2] += R

    def d2_of(pairs):
        """Joint d² of a hypothesis given as (measurement, landmark) pairs."""
        i, j = np.array(pairs).T
        rows = (2 * j[:, None] + (0, 1)).ravel()
        v = nu[i, j].ravel()
        return float(v @ np.linalg.solve(s_all[np.ix_(rows, rows)], v))

    # individual compatibility of every pair at once, against the χ²₂ quantile -2 ln(1 - p)
    blocks = s_all.reshape(n_lm, 2, n_lm, 2)[lm, :, lm, :]
    single = np.einsum("ija,jab,ijb->ij", nu, np.linalg.inv(blocks), nu)
    ok = (single < -2 * math.log(1 - confidence)).tolist()
    best_pairs, best_d2 = [], 0.0

    def search(i, pairs, d2):
        """Extend the jointly compatible ``pairs`` (joint d² ``d2``) from measurement ``i``."""
        nonlocal best_pairs, best_d2
        if i == m:
            if len(pairs) > len(best_pairs) or (len(pairs) == len(best_pairs) and d2 < best_d2):
                best_pairs, best_d2 = pairs, d2
            return
        used = {j for _, j in pairs}
        for j in range(n_lm):
            if ok[i][j] and j not in used:
                trial = [*pairs, (i, j)]
                trial_d2 = d2_of(trial)
                if _chi2_below(trial_d2, 2 * len(trial), confidence):
                    search(i + 1, trial, trial_d2)
        if len(pairs) + (m - i - 1) >= len(best_pairs):  # can leaving i unpaired still tie?
            search(i + 1, pairs, d2)

    search(0, [], 0.0)
    out = [-1] * m
    for i, j in best_pairs:
        out[i] = j
    return out
