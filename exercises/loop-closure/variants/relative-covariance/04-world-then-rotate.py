# method: the covariance of the world-frame difference and of the headings first, then the rotation into pose i's frame plus the lever arm
import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    # w = (tj - ti, theta_i, theta_j) is linear in the poses: w = L x
    L = np.zeros((4, 6))
    L[0, 0], L[0, 3] = -1.0, 1.0
    L[1, 1], L[1, 4] = -1.0, 1.0
    L[2, 2] = 1.0
    L[3, 5] = 1.0
    W = L @ np.asarray(P, dtype=float) @ L.T
    # r = (R_i^T d, theta_j - theta_i) linearised in w
    th = float(xi[2])
    d = np.array([float(xj[0]) - float(xi[0]), float(xj[1]) - float(xi[1])])
    rt = np.array([[math.cos(th), math.sin(th)], [-math.sin(th), math.cos(th)]])
    r_xy = rt @ d
    M = np.zeros((3, 4))
    M[:2, :2] = rt
    M[:2, 2] = [r_xy[1], -r_xy[0]]  # d(R^T d)/dtheta = -[[0, -1], [1, 0]] R^T d
    M[2, 2], M[2, 3] = -1.0, 1.0
    return M @ W @ M.T
