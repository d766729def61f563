# mistake: theta / (2 sin theta) times the antisymmetric part everywhere (nothing special near pi)
import math

import numpy as np


def so3_log(R):
    R = np.array(R, dtype=float)
    v = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    s = np.linalg.norm(v)
    c = (np.trace(R) - 1) / 2
    theta = math.atan2(s, c)
    if theta < 1e-4:
        return (1 + theta**2 / 6) * v
    return theta / math.sin(theta) * v
