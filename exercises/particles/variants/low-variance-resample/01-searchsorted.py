# method: numpy: normalised cumulative sum and np.searchsorted for all thresholds at once
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w / w.sum())
    idx = np.searchsorted(c, (u + np.arange(n)) / n, side="left")
    return np.minimum(idx, n - 1)
