# mistake: allocates the result with np.zeros_like of the input, which is an integer array when P holds whole numbers
import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    P = np.asarray(P)
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    J = np.array(
        [
            [-ci, -si, -si * dx + ci * dy, ci, si, 0.0],
            [si, -ci, -ci * dx - si * dy, -si, ci, 0.0],
            [0.0, 0.0, -1.0, 0.0, 0.0, 1.0],
        ]
    )
    out = np.zeros_like(P[:3, :3])
    out[:, :] = J @ P @ J.T
    return out
