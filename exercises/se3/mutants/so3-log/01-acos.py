# mistake: the angle from acos of the trace, the axis from the antisymmetric part over 2 sin(theta)
import math

import numpy as np


def so3_log(R):
    R = np.array(R, dtype=float)
    theta = math.acos(max(-1.0, min(1.0, (np.trace(R) - 1) / 2)))
    if theta < 1e-10:
        return np.zeros(3)
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return theta / (2 * math.sin(theta)) * v
