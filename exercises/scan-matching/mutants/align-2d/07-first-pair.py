# mistake: the angle from the first two correspondences only, exact without noise, wrong with it
import math

import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    dp, dq = P[1] - P[0], Q[1] - Q[0]
    theta = math.atan2(dq[1], dq[0]) - math.atan2(dp[1], dp[0])
    theta = math.atan2(math.sin(theta), math.cos(theta))
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = Q.mean(axis=0) - R @ P.mean(axis=0)
    return [theta, float(t[0]), float(t[1])]
