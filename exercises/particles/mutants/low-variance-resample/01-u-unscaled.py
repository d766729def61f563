# mistake: uses the thresholds u + m/N, forgetting to divide u by N too
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    idx = np.searchsorted(c, u + np.arange(n) / n)
    return np.minimum(idx, n - 1)
