# mistake: one degree of freedom per pairing (k instead of 2k)
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
    k = len(nu) // 2
    x = d2_of(H, P, R, nu)
    if k % 2:  # odd k: χ²_k from the normal distribution for k = 1, else the series by 2s
        from statistics import NormalDist

        p = 2 * NormalDist().cdf(math.sqrt(x)) - 1
        if k == 3:
            p -= math.sqrt(2 * x / math.pi) * math.exp(-x / 2)
        return p < confidence
    return cdf_even(x, k) < confidence
