# mistake: numbers the new particles m = 1..N, so every threshold is one step too far
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    idx = np.searchsorted(c, (u + np.arange(1, n + 1)) / n)
    return np.minimum(idx, n - 1)
