# mistake: theta / |v| times v down to the smallest angles, with no case for theta = 0 (0/0 at I)
import math

import numpy as np


def so3_log(R):
    m = np.array(R, dtype=float)
    v = 0.5 * np.array([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])
    s = float(np.linalg.norm(v))
    c = (np.trace(m) - 1) / 2
    theta = math.atan2(s, c)
    if theta < math.pi - 0.1:  # theta/sin(theta) is accurate even at 1e-9: no series needed
        with np.errstate(invalid="ignore", divide="ignore"):
            return theta / np.float64(s) * v
    b = (m + m.T) / 2 - c * np.eye(3)
    k = int(np.argmax(np.diag(b)))
    n = b[:, k] / np.linalg.norm(b[:, k])
    if n @ v < 0:
        n = -n
    return theta * n
