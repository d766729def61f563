# mistake: only the translation is estimated (theta = 0, t = difference of the centroids)
import numpy as np


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    M = Q[np.argmin(((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2), axis=1)]
    t = M.mean(axis=0) - P.mean(axis=0)
    return [0.0, float(t[0]), float(t[1])]
