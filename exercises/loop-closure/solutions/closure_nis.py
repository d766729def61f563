import math

import numpy as np


def wrap(a):
    a = math.fmod(a + math.pi, 2 * math.pi)
    if a <= 0:
        a += 2 * math.pi
    return a - math.pi


def rot_t(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s], [-s, c]])


def closure_nis(xi, xj, P, z, info):
    ti = np.array([xi[0], xi[1]], dtype=float)
    tj = np.array([xj[0], xj[1]], dtype=float)
    tz = np.array([z[0], z[1]], dtype=float)
    ri_t, rz_t = rot_t(xi[2]), rot_t(z[2])
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    d_ri_t = np.array([[-si, ci], [-ci, -si]])
    e = np.zeros(3)
    e[:2] = rz_t @ (ri_t @ (tj - ti) - tz)
    e[2] = wrap(xj[2] - xi[2] - z[2])
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    A[:2, :2] = -rz_t @ ri_t
    A[:2, 2] = rz_t @ d_ri_t @ (tj - ti)
    A[2, 2] = -1.0
    B[:2, :2] = rz_t @ ri_t
    B[2, 2] = 1.0
    J = np.hstack([A, B])
    P = np.asarray(P, dtype=float)
    S = J @ P @ J.T + np.linalg.inv(np.array(info, dtype=float))
    return float(e @ np.linalg.solve(S, e))
