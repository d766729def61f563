# mistake: uses the covariance of the relative pose (Jacobians without R_z^T) for the innovation e, which is expressed in the measurement's frame
import math

import numpy as np


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def closure_nis(xi, xj, P, z, info):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    cz, sz = math.cos(z[2]), math.sin(z[2])
    ri_t = np.array([[ci, si], [-si, ci]])
    rz_t = np.array([[cz, sz], [-sz, cz]])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]], dtype=float)
    e = np.zeros(3)
    e[:2] = rz_t @ (ri_t @ d - np.array([z[0], z[1]], dtype=float))
    e[2] = wrap(xj[2] - xi[2] - z[2])
    J = np.zeros((3, 6))
    J[:2, :2] = -ri_t
    J[:2, 2] = np.array([[-si, ci], [-ci, -si]]) @ d
    J[2, 2] = -1.0
    J[:2, 3:5] = ri_t
    J[2, 5] = 1.0
    P = np.asarray(P, dtype=float)
    S = J @ P @ J.T + np.linalg.inv(np.array(info, dtype=float))
    return float(e @ np.linalg.solve(S, e))
