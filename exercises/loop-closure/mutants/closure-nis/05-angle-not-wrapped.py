# mistake: the angle of the innovation is not wrapped
import math

import numpy as np


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def parts(xi, xj, z):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    cz, sz = math.cos(z[2]), math.sin(z[2])
    ri_t = np.array([[ci, si], [-si, ci]])
    rz_t = np.array([[cz, sz], [-sz, cz]])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]], dtype=float)
    e = np.zeros(3)
    e[:2] = rz_t @ (ri_t @ d - np.array([z[0], z[1]], dtype=float))
    e[2] = xj[2] - xi[2] - z[2]
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    A[:2, :2] = -rz_t @ ri_t
    A[:2, 2] = rz_t @ np.array([[-si, ci], [-ci, -si]]) @ d
    A[2, 2] = -1.0
    B[:2, :2] = rz_t @ ri_t
    B[2, 2] = 1.0
    return e, A, B


def closure_nis(xi, xj, P, z, info):
    e, A, B = parts(xi, xj, z)
    P = np.asarray(P, dtype=float)
    J = np.hstack([A, B])
    S = J @ P @ J.T + np.linalg.inv(np.array(info, dtype=float))
    return float(e @ np.linalg.solve(S, e))
