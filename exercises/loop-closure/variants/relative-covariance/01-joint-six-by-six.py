# method: one 3x6 Jacobian built column block by column block, J P J^T, returned as a list
import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    c, s = math.cos(xi[2]), math.sin(xi[2])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]], dtype=float)
    rt = np.array([[c, s], [-s, c]])
    drt = np.array([[-s, c], [-c, -s]])
    J = np.zeros((3, 6))
    J[:2, :2] = -rt
    J[:2, 2] = drt @ d
    J[2, 2] = -1.0
    J[:2, 3:5] = rt
    J[2, 5] = 1.0
    return (J @ np.asarray(P, dtype=float) @ J.T).tolist()
