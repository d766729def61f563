import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    ri_t = np.array([[ci, si], [-si, ci]])
    d_ri_t = np.array([[-si, ci], [-ci, -si]])
    Ji = np.zeros((3, 3))
    Jj = np.zeros((3, 3))
    Ji[:2, :2] = -ri_t
    Ji[:2, 2] = d_ri_t @ np.array([dx, dy])
    Ji[2, 2] = -1.0
    Jj[:2, :2] = ri_t
    Jj[2, 2] = 1.0
    J = np.hstack([Ji, Jj])
    return J @ np.array(P, dtype=float) @ J.T
