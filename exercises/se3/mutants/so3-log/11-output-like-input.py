# mistake: the result array made with np.zeros_like(R[0]), so a matrix of whole numbers truncates it
import math

import numpy as np


def so3_log(R):
    m = np.asarray(R)
    w = np.zeros_like(m[0])  # the output: three numbers, "like a row of R"
    v = 0.5 * np.array([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])
    s = float(np.linalg.norm(v))
    c = (float(np.trace(m)) - 1) / 2
    theta = math.atan2(s, c)
    if theta < 1e-4:
        w[:] = (1 + theta**2 / 6) * v
    elif theta < math.pi - 0.1:
        w[:] = theta / s * v
    else:
        b = (m + m.T) / 2 - c * np.eye(3)
        k = int(np.argmax(np.diag(b)))
        n = b[:, k] / np.linalg.norm(b[:, k])
        if n @ v < 0:
            n = -n
        w[:] = theta * n
    return w
