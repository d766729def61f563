# method: innovation (xi^-1 (+) xj) - z in pose i's frame, with the measurement covariance rotated into that frame, R_z Omega^-1 R_z^T
import math

import numpy as np


def closure_nis(xi, xj, P, z, info):
    th = float(xi[2])
    c, s = math.cos(th), math.sin(th)
    rt = np.array([[c, s], [-s, c]])
    d = np.array([float(xj[0]) - float(xi[0]), float(xj[1]) - float(xi[1])])
    r = rt @ d
    dth = math.remainder(float(xj[2]) - th - float(z[2]), 2 * math.pi)
    nu = np.array([r[0] - float(z[0]), r[1] - float(z[1]), dth])
    J = np.zeros((3, 6))
    J[:2, :2] = -rt
    J[:2, 2] = [r[1], -r[0]]
    J[2, 2] = -1.0
    J[:2, 3:5] = rt
    J[2, 5] = 1.0
    P = np.asarray(P, float)
    cz, sz = math.cos(float(z[2])), math.sin(float(z[2]))
    T = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    S = J @ P @ J.T + T @ np.linalg.inv(np.asarray(info, float)) @ T.T
    return float(nu @ np.linalg.solve(S, nu))
