# method: closed form with the combined rotation R(theta_i + theta_z)^T
import math

import numpy as np


def edge_jacobians(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2] + z[2]), math.sin(xi[2] + z[2])
    R = np.array([[c, s], [-s, c]])  # Rz^T Ri^T
    # d/dtheta_i of Rz^T Ri^T d equals Rz^T Ri^T [[0, 1], [-1, 0]] d
    col = R @ np.array([dy, -dx])
    J = np.zeros((3, 6))
    J[:2, :2] = -R
    J[:2, 2] = col
    J[2, 2] = -1.0
    J[:2, 3:5] = R
    J[2, 5] = 1.0
    return J
