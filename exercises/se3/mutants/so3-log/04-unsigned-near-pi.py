# mistake: near pi the axis from the symmetric part, its sign never checked (largest kept positive)
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
    if theta < math.pi - 0.1:
        return theta / s * v
    B = (R + R.T) / 2 - c * np.eye(3)
    k = int(np.argmax(np.diag(B)))
    n = B[:, k] / np.linalg.norm(B[:, k])
    return theta * n
