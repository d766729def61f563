# method: homogeneous matrices, inv(Z) @ inv(Xi) @ Xj read back as a pose
import numpy as np


def T(p):
    c, s = np.cos(p[2]), np.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0.0, 0.0, 1.0]])


def edge_error(xi, xj, z):
    E = np.linalg.inv(T(z)) @ np.linalg.inv(T(xi)) @ T(xj)
    return np.array([E[0, 2], E[1, 2], np.arctan2(E[1, 0], E[0, 0])])
