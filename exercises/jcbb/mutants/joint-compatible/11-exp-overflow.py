# mistake: divides the series by exp(d2/2) instead of multiplying by exp(-d2/2), which overflows for a far-off hypothesis (d2 above about 1420)
import math

import numpy as np


def joint_compatible(H, P, R, nu, confidence):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    x = float(nu @ np.linalg.solve(S, nu)) / 2
    cdf = 1 - sum(x**i / math.factorial(i) for i in range(k)) / math.exp(x)
    return cdf < confidence
