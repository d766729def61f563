# mistake: centres the points in place in np.asarray(P, dtype=float), which is the caller's own array when P is a float array
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    P -= pm
    b = Q - qm
    s = np.sum(P[:, 0] * b[:, 1] - P[:, 1] * b[:, 0])
    c = np.sum(P * b)
    theta = float(np.arctan2(s, c))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
