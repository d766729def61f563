# method: whitens the innovation with a Cholesky factor of S and returns its squared norm
import math

import numpy as np


def closure_nis(xi, xj, P, z, info):
    xi, xj, z = (np.asarray(v, dtype=float) for v in (xi, xj, z))
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    cz, sz = math.cos(z[2]), math.sin(z[2])
    Ri = np.array([[ci, -si], [si, ci]])
    Rz = np.array([[cz, -sz], [sz, cz]])
    d = xj[:2] - xi[:2]
    e_xy = Rz.T @ (Ri.T @ d - z[:2])
    e_th = math.atan2(math.sin(xj[2] - xi[2] - z[2]), math.cos(xj[2] - xi[2] - z[2]))
    e = np.array([e_xy[0], e_xy[1], e_th])
    dRiT = np.array([[-si, ci], [-ci, -si]])
    J = np.zeros((3, 6))
    J[:2, 0:2] = -Rz.T @ Ri.T
    J[:2, 2] = Rz.T @ dRiT @ d
    J[2, 2] = -1
    J[:2, 3:5] = Rz.T @ Ri.T
    J[2, 5] = 1
    P = np.asarray(P, dtype=float)
    S = J @ P @ J.T + np.linalg.inv(np.asarray(info, dtype=float))
    L = np.linalg.cholesky((S + S.T) / 2)
    w = np.linalg.solve(L, e)
    return float(w @ w)
