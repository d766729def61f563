# mistake: atan(S / C) instead of atan2(S, C): wrong by π when C < 0 (turns beyond ±90°)
import math

import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    a, b = P - pm, Q - qm
    s = float(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))
    c = float(np.sum(a * b))
    theta = math.atan(s / c) if c != 0 else math.copysign(math.pi / 2, s)
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
