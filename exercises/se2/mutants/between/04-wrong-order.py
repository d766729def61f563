# mistake: composes in the wrong order, b (+) a^-1 instead of a^-1 (+) b
import numpy as np


def T(p):
    c, s = np.cos(p[2]), np.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0, 0, 1]])


def between(a, b):
    M = T(b) @ np.linalg.inv(T(a))
    return M[0, 2], M[1, 2], np.arctan2(M[1, 0], M[0, 0])
