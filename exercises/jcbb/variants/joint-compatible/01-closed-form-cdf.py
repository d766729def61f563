# method: the closed-form distribution function of χ² with 2k degrees of freedom
import math

import numpy as np


def joint_compatible(H, P, R, nu, confidence):
    H, P, R, nu = (np.asarray(a, dtype=float) for a in (H, P, R, nu))
    k = nu.size // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    x = nu @ np.linalg.solve(S, nu) / 2
    term, total = 1.0, 1.0
    for i in range(1, k):
        term *= x / i
        total += term
    return bool(1 - math.exp(-x) * total < confidence)
