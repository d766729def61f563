# mistake: searches the normalised weights themselves instead of their cumulative sum
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = w / w.sum()
    return np.minimum(np.searchsorted(c, (u + np.arange(n)) / n), n - 1)
