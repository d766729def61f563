# mistake: the kernel's cost rho(s) returned instead of its derivative
import numpy as np


def robust_weights(kind, s, k):
    s = np.asarray(s, dtype=float).reshape(-1)
    k2 = k * k
    if kind == "l2":
        return s
    if kind == "huber":
        return np.where(s <= k2, s, 2 * k * np.sqrt(s) - k2)
    if kind == "cauchy":
        return k2 * np.log1p(s / k2)
    if kind == "dcs":
        return np.where(s <= k2, s, k2 * (3 * s - k2) / (k2 + s))
    raise ValueError(kind)
