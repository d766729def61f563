import math

import numpy as np


def joint_compatible(H, P, R, nu, confidence):
    """True when the stacked innovation passes the joint χ² gate with 2k degrees of freedom."""
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    x = float(nu @ np.linalg.solve(S, nu)) / 2
    cdf = 1 - math.exp(-x) * sum(x**i / math.factorial(i) for i in range(k))
    return cdf < confidence
