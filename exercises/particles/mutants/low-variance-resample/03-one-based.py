# mistake: returns 1-based indices, as in the book's pseudocode
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    idx = np.minimum(np.searchsorted(c, (u + np.arange(n)) / n), n - 1)
    return idx + 1
