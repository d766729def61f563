# method: G and V by central finite differences of the motion model
import math

import numpy as np


def step(p, u):
    h = p[2] + u[0]
    return np.array([p[0] + u[1] * math.cos(h), p[1] + u[1] * math.sin(h), p[2] + u[0] + u[2]])


def jacobian(f, x0, eps=1e-6):
    x0 = np.asarray(x0, dtype=float)
    cols = []
    for k in range(3):
        d = np.zeros(3)
        d[k] = eps
        cols.append((f(x0 + d) - f(x0 - d)) / (2 * eps))
    return np.column_stack(cols)


def predict_covariance(pose, u, sigma, motion_cov):
    G = jacobian(lambda p: step(p, u), pose)
    V = jacobian(lambda q: step(pose, q), u)
    return G @ np.asarray(sigma) @ G.T + V @ np.asarray(motion_cov) @ V.T
