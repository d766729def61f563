# mistake: finds the nearest point with min() and its index with Q.index(q), which a numpy array does not have
import math

import numpy as np


def icp_step(P, Q):
    matched = []
    for p in P:
        q = min(Q, key=lambda q: math.hypot(q[0] - p[0], q[1] - p[1]))
        matched.append(Q[Q.index(q)])
    a, b = np.array(P, dtype=float), np.array(matched, dtype=float)
    pm, qm = a.mean(axis=0), b.mean(axis=0)
    a, b = a - pm, b - qm
    theta = float(np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b)))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
