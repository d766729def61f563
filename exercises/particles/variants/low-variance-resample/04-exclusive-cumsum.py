# method: the cumulative sum starting at 0 (where each particle's interval starts) and the last start below each threshold
import numpy as np


def low_variance_resample(weights, u):
    w = np.asarray(weights, dtype=float)
    n = len(w)
    starts = np.concatenate([[0.0], np.cumsum(w)[:-1]]) / w.sum()
    thresholds = (u + np.arange(n)) / n
    return (np.searchsorted(starts, thresholds, side="left") - 1).clip(0, n - 1).tolist()
