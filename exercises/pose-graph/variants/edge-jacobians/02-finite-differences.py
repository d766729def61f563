# method: central finite differences of the edge error, angle difference wrapped
import math

import numpy as np


def edge_error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    ux, uy = c * dx + s * dy - z[0], -s * dx + c * dy - z[1]
    cz, sz = math.cos(z[2]), math.sin(z[2])
    return np.array([cz * ux + sz * uy, -sz * ux + cz * uy, xj[2] - xi[2] - z[2]])


def edge_jacobians(xi, xj, z, h=1e-6):
    xi, xj = np.asarray(xi, dtype=float), np.asarray(xj, dtype=float)
    cols = []
    for which in (0, 1):
        for k in range(3):
            d = np.zeros(3)
            d[k] = h
            if which == 0:
                diff = edge_error(xi + d, xj, z) - edge_error(xi - d, xj, z)
            else:
                diff = edge_error(xi, xj + d, z) - edge_error(xi, xj - d, z)
            diff[2] = math.remainder(diff[2], 2 * math.pi)
            cols.append(diff / (2 * h))
    return np.column_stack(cols)
