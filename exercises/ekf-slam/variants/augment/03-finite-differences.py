# method: G_r and G_z by central finite differences of the inverse observation model
import math

import numpy as np


def g(x, y, t, r, phi):
    return np.array([x + r * math.cos(t + phi), y + r * math.sin(t + phi)])


def jacobian(f, point, step=1e-5):
    point = np.array(point, dtype=float)
    cols = []
    for k in range(len(point)):
        d = np.zeros_like(point)
        d[k] = step
        cols.append((f(*(point + d)) - f(*(point - d))) / (2 * step))
    return np.stack(cols, axis=1)


def augment(mu, P, z, R):
    P, R = np.array(P, dtype=float), np.array(R, dtype=float)
    n = len(P)
    pose = [float(v) for v in mu[:3]]
    Gr = jacobian(lambda x, y, t: g(x, y, t, z[0], z[1]), pose)
    Gz = jacobian(lambda r, phi: g(*pose, r, phi), z)
    out = np.zeros((n + 2, n + 2))
    out[:n, :n] = P
    out[n:, :n] = Gr @ P[:3, :]
    out[:n, n:] = out[n:, :n].T
    out[n:, n:] = Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T
    return out
