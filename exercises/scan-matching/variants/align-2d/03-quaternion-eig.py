# method: the 2-D analogue of Horn's method: the top eigenvector (cos, sin) of the symmetric form [[C, S], [S, -C]]
import math

import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    a, b = P - pm, Q - qm
    C = float(np.sum(a * b))
    S = float(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))
    # maximise C cos θ + S sin θ: in half-angle terms (u, v) = (cos θ/2, sin θ/2) this is the
    # quadratic form [u v] [[C, S], [S, -C]] [u v]ᵀ over the unit circle
    w, V = np.linalg.eigh(np.array([[C, S], [S, -C]]))
    u, v = V[:, int(np.argmax(w))]
    theta = 2.0 * math.atan2(v, u)
    c, s = math.cos(theta), math.sin(theta)
    t = qm - np.array([c * pm[0] - s * pm[1], s * pm[0] + c * pm[1]])
    return [theta, float(t[0]), float(t[1])]
