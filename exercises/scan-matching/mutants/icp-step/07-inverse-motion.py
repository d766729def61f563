# mistake: returns the motion taking the matched Q points onto P (the inverse)
import numpy as np

def _align(P, M):
    pm, qm = P.mean(axis=0), M.mean(axis=0)
    a, b = P - pm, M - qm
    theta = float(np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    M = Q[np.argmin(((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2), axis=1)]
    return _align(M, P)
