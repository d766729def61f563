# method: the gate itself, found by bisection on the distribution function, then d² < gate
import math

import numpy as np


def cdf(x, k):
    h = x / 2
    return 1 - math.exp(-h) * sum(h**i / math.factorial(i) for i in range(k))


def joint_compatible(H, P, R, nu, confidence):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T
    for i in range(k):
        S[2 * i : 2 * i + 2, 2 * i : 2 * i + 2] += R
    d2 = float(nu @ np.linalg.inv(S) @ nu)
    lo, hi = 0.0, 100.0
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if cdf(mid, k) < confidence else (lo, mid)
    return d2 < hi
