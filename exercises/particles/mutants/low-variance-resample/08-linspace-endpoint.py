# mistake: spreads the thresholds with np.linspace up to and including 1 (spacing 1/(N-1))
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    thresholds = np.linspace(u / n, 1.0, n)
    return np.minimum(np.searchsorted(c, thresholds), n - 1)
