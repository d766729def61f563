# mistake: normalises the caller's weights in place
import numpy as np


def low_variance_resample(weights, u):
    total = sum(weights)
    for k in range(len(weights)):
        weights[k] = weights[k] / total
    n = len(weights)
    c = np.cumsum(weights)
    return np.minimum(np.searchsorted(c, (u + np.arange(n)) / n), n - 1)
