# mistake: the angle from the raw points, not centred: right only when both centroids are at the origin
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    theta = float(np.arctan2(np.sum(P[:, 0] * Q[:, 1] - P[:, 1] * Q[:, 0]), np.sum(P * Q)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = Q.mean(axis=0) - R @ P.mean(axis=0)
    return [theta, float(t[0]), float(t[1])]
