# mistake: ties in the nearest-neighbour search go to the larger index (the last minimum found)
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
    pairs = []
    for p in P:
        best, best_d = 0, float("inf")
        for j, q in enumerate(Q):
            d = float(np.sum((p - q) ** 2))
            if d <= best_d:
                best, best_d = j, d
        pairs.append(best)
    return _align(P, Q[pairs])
