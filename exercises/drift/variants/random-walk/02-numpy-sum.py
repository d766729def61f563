# method: numpy: sum the per-step variances of an array, then np.sqrt (returns a numpy float)
import numpy as np


def random_walk_error(sigma, steps):
    variances = np.full(steps, sigma ** 2, dtype=np.float64)
    return np.sqrt(variances.sum())
