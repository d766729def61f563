# mistake: G_z's columns in the order (φ, r) while R is in the order (r, φ)
import math

import numpy as np


def augment(mu, P, z, R):
    P, R = np.array(P, dtype=float), np.array(R, dtype=float)
    n = len(P)
    r, a = z[0], mu[2] + z[1]
    c, s = math.cos(a), math.sin(a)
    Gr = np.array([[1.0, 0.0, -r * s], [0.0, 1.0, r * c]])
    Gz = np.array([[-r * s, c], [r * c, s]])
    cross = Gr @ P[:3, :]
    out = np.zeros((n + 2, n + 2))
    out[:n, :n] = P
    out[n:, :n] = cross
    out[:n, n:] = cross.T
    out[n:, n:] = Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T
    return out
