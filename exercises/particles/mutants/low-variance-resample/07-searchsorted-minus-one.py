# mistake: subtracts one from np.searchsorted, as if it returned the interval's left end
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    idx = np.searchsorted(c, (u + np.arange(n)) / n) - 1
    return np.clip(idx, 0, n - 1)
