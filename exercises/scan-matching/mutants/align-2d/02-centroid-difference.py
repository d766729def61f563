# mistake: t = q̄ − p̄, the centroid of P not rotated
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    a, b = P - pm, Q - qm
    theta = float(np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b)))
    t = qm - pm
    return [theta, float(t[0]), float(t[1])]
