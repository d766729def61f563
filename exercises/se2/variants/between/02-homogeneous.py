# method: homogeneous 3x3 matrices, inv(T(a)) @ T(b), angle read back with atan2
import numpy as np


def T(p):
    c, s = np.cos(p[2]), np.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0.0, 0.0, 1.0]])


def between(a, b):
    M = np.linalg.inv(T(a)) @ T(b)
    return np.array([M[0, 2], M[1, 2], np.arctan2(M[1, 0], M[0, 0])])
