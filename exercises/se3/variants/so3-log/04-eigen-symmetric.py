# method: the axis as the eigenvector of the symmetric part with the largest eigenvalue (near pi)
import math

import numpy as np


def so3_log(R):
    m = np.asarray(R, dtype=float)
    v = 0.5 * np.array([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])
    s = float(np.linalg.norm(v))
    c = (float(np.trace(m)) - 1) / 2
    theta = math.atan2(s, c)
    if theta < 1e-3:
        return (1 + theta * theta / 6 + 7 * theta**4 / 360) * v
    if theta < 2.5:
        return (theta / s) * v
    values, vectors = np.linalg.eigh((m + m.T) / 2)
    n = vectors[:, int(np.argmax(values))]
    d = float(n @ v)
    if d < 0 or (d == 0 and n[int(np.argmax(np.abs(n)))] < 0):
        n = -n
    return theta * n
