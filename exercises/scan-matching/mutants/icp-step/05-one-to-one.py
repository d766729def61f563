# mistake: greedy one-to-one matching: a point of Q already used is not offered again
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
    used = set()
    pairs = []
    for p in P:
        d2 = ((Q - p) ** 2).sum(axis=1)
        for j in np.argsort(d2, kind="stable"):
            if int(j) not in used or len(used) == len(Q):
                used.add(int(j))
                pairs.append(int(j))
                break
    return _align(P, Q[pairs])
