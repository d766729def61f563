# method: numpy: all d2 at once, outside-gate ones set to inf, argmin (first of ties), numpy int
import numpy as np


def nearest_neighbour(z, landmarks, s00, s11, gate):
    h = np.array(landmarks, dtype=float).reshape(-1, 2)
    if len(h) == 0:
        return -1
    nu = np.asarray(z, dtype=float) - h
    d2 = nu @ np.diag([1 / s00, 1 / s11]) * nu
    d2 = d2.sum(axis=1)
    masked = np.where(d2 < gate, d2, np.inf)
    j = np.argmin(masked)
    return j if np.isfinite(masked[j]) else np.int64(-1)
