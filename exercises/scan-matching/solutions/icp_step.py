import numpy as np


def icp_step(P, Q):
    """One ICP iteration from the identity: [theta, tx, ty]."""
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    d2 = ((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2)
    M = Q[np.argmin(d2, axis=1)]
    pm, qm = P.mean(axis=0), M.mean(axis=0)
    a, b = P - pm, M - qm
    theta = float(np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
