# method: one Jacobian J of (x, z) ↦ (x, g(x_r, z)), then P' = J blockdiag(P, R) Jᵀ
import math

import numpy as np


def augment(mu, P, z, R):
    P, R = np.array(P, dtype=float), np.array(R, dtype=float)
    n = len(P)
    r, a = z[0], mu[2] + z[1]
    c, s = math.cos(a), math.sin(a)
    J = np.zeros((n + 2, n + 2))
    J[:n, :n] = np.eye(n)
    J[n:, :3] = [[1.0, 0.0, -r * s], [0.0, 1.0, r * c]]
    J[n:, n:] = [[c, -r * s], [s, r * c]]
    joint = np.zeros((n + 2, n + 2))
    joint[:n, :n] = P
    joint[n:, n:] = R
    return J @ joint @ J.T
