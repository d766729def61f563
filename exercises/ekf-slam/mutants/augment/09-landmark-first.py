# mistake: the new landmark inserted before the pose instead of appended last
import math

import numpy as np


def augment(mu, P, z, R):
    P, R = np.array(P, dtype=float), np.array(R, dtype=float)
    n = len(P)
    r, a = z[0], mu[2] + z[1]
    c, s = math.cos(a), math.sin(a)
    Gr = np.array([[1.0, 0.0, -r * s], [0.0, 1.0, r * c]])
    Gz = np.array([[c, -r * s], [s, r * c]])
    cross = Gr @ P[:3, :]
    out = np.zeros((n + 2, n + 2))
    out[2:, 2:] = P
    out[:2, 2:] = cross
    out[2:, :2] = cross.T
    out[:2, :2] = Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T
    return out
