# mistake: sorts the weights before accumulating them, so the indices refer to the sorted order
import numpy as np


def low_variance_resample(weights, u):
    w = np.sort(np.asarray(weights, dtype=float))[::-1]
    n = len(w)
    c = np.cumsum(w) / w.sum()
    return np.minimum(np.searchsorted(c, (u + np.arange(n)) / n), n - 1)
