# mistake: the translation uses the centroid of the whole reference scan, not of the matched points
import numpy as np


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    M = Q[np.argmin(((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2), axis=1)]
    pm, mm = P.mean(axis=0), M.mean(axis=0)
    a, b = P - pm, M - mm
    theta = float(np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = Q.mean(axis=0) - R @ pm
    return [theta, float(t[0]), float(t[1])]
