# mistake: the series without its factorials
import math

import numpy as np


def d2_of(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    return float(nu @ np.linalg.solve(S, nu))


def cdf_even(x2, dof):
    x, k = x2 / 2, dof // 2
    return 1 - math.exp(-x) * sum(x**i / math.factorial(i) for i in range(k))


def joint_compatible(H, P, R, nu, confidence):
    x, k = d2_of(H, P, R, nu) / 2, len(nu) // 2
    cdf = 1 - math.exp(-x) * sum(x**i for i in range(k))
    return cdf < confidence
