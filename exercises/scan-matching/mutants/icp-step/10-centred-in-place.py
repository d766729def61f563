# mistake: centres the new scan in place in np.asarray(P, dtype=float), which is the caller's own array when P is a float array
import numpy as np


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    d2 = ((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2)
    M = Q[np.argmin(d2, axis=1)]
    pm, qm = P.mean(axis=0), M.mean(axis=0)
    P -= pm
    b = M - qm
    theta = float(np.arctan2(np.sum(P[:, 0] * b[:, 1] - P[:, 1] * b[:, 0]), np.sum(P * b)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
