# method: written with the normalised distance r = sqrt(s) / k, numpy throughout
import numpy as np


def robust_weights(kind, s, k):
    r = np.sqrt(np.array(s, dtype=float)) / k  # the error in units of the kernel width
    if kind == "huber":
        return 1.0 / np.maximum(r, 1.0)
    if kind == "cauchy":
        return 1.0 / (1.0 + r * r)
    if kind == "dcs":
        return np.minimum(1.0, 2.0 / (1.0 + r * r)) ** 2
    return np.ones_like(r)
