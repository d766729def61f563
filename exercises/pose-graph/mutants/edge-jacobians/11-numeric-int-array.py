# mistake: central differences on np.array(xi) and np.array(xj), integer arrays when the poses hold whole numbers, so the step is truncated away
import math

import numpy as np


def _error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    x, y = c * dx + s * dy - z[0], -s * dx + c * dy - z[1]
    cz, sz = math.cos(z[2]), math.sin(z[2])
    return np.array([cz * x + sz * y, -sz * x + cz * y, xj[2] - xi[2] - z[2]])


def edge_jacobians(xi, xj, z):
    xi, xj = np.array(xi), np.array(xj)
    J = np.zeros((3, 6))
    h = 1e-6
    for k in range(6):
        pi, pj, mi, mj = xi.copy(), xj.copy(), xi.copy(), xj.copy()
        if k < 3:
            pi[k] += h
            mi[k] -= h
        else:
            pj[k - 3] += h
            mj[k - 3] -= h
        J[:, k] = (_error(pi, pj, z) - _error(mi, mj, z)) / (2 * h)
    return J
