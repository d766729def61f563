# method: Jacobians of xi^-1 (+) xj by complex-step differentiation (exact to rounding)
import cmath

import numpy as np


def between(p, q):
    c, s = cmath.cos(p[2]), cmath.sin(p[2])
    dx, dy = q[0] - p[0], q[1] - p[1]
    return np.array([c * dx + s * dy, -s * dx + c * dy, q[2] - p[2]])


def relative_pose_covariance(xi, xj, P):
    x = np.concatenate([np.asarray(xi, dtype=float), np.asarray(xj, dtype=float)])
    h = 1e-30
    J = np.zeros((3, 6))
    for k in range(6):
        y = x.astype(complex)
        y[k] += 1j * h
        J[:, k] = between(y[:3], y[3:]).imag / h
    return J @ np.asarray(P, dtype=float) @ J.T
