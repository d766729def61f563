# mistake: takes the innovation as (xi^-1 (+) xj) - z in pose i's frame but adds Omega^-1 without rotating it into that frame
import math

import numpy as np


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def closure_nis(xi, xj, P, z, info):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    ri_t = np.array([[ci, si], [-si, ci]])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]], dtype=float)
    r = ri_t @ d
    nu = np.array([r[0] - z[0], r[1] - z[1], wrap(xj[2] - xi[2] - z[2])])
    J = np.zeros((3, 6))
    J[:2, :2] = -ri_t
    J[:2, 2] = np.array([[-si, ci], [-ci, -si]]) @ d
    J[2, 2] = -1.0
    J[:2, 3:5] = ri_t
    J[2, 5] = 1.0
    P = np.asarray(P, dtype=float)
    S = J @ P @ J.T + np.linalg.inv(np.array(info, dtype=float))
    return float(nu @ np.linalg.solve(S, nu))
