# mistake: differentiates with the rotation matrix itself: uses Ri^T d instead of d(Ri^T)/dtheta d
import math

import numpy as np


def rot_t(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s], [-s, c]])


def edge_jacobians(xi, xj, z):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]])
    rz_t = rot_t(z[2])
    ri_t = rot_t(xi[2])
    d_ri_t = np.array([[-si, ci], [-ci, -si]])
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    A[:2, :2] = -rz_t @ ri_t
    A[:2, 2] = rz_t @ ri_t @ d
    A[2, 2] = -1.0
    B[:2, :2] = rz_t @ ri_t
    B[2, 2] = 1.0
    return np.hstack([A, B])
