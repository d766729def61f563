# mistake: R - R^T computed in place on np.asarray(R), which changes the caller's array
import math

import numpy as np


def so3_log(R):
    m = np.asarray(R, dtype=float)  # no copy when R already is a float array
    c = (np.trace(m) - 1) / 2
    b = (m + m.T) / 2 - c * np.eye(3)  # the symmetric part, kept for angles near pi
    m -= m.T  # the antisymmetric part, without another array
    v = 0.5 * np.array([m[2, 1], m[0, 2], m[1, 0]])
    s = float(np.linalg.norm(v))
    theta = math.atan2(s, c)
    if theta < 1e-4:
        return (1 + theta**2 / 6) * v
    if theta < math.pi - 0.1:
        return theta / s * v
    k = int(np.argmax(np.diag(b)))
    n = b[:, k] / np.linalg.norm(b[:, k])
    if n @ v < 0:
        n = -n
    return theta * n
