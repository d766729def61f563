# mistake: the Mahalanobis distance d, not its square, against the gate
import math

import numpy as np


def relative_jacobians(xi, xk):
    c, s = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xk[0] - xi[0], xk[1] - xi[1]
    ji = np.array([[-c, -s, -s * dx + c * dy], [s, -c, -c * dx - s * dy], [0.0, 0.0, -1.0]])
    jk = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return ji, jk


def d2_of(x, m, c, i, k):
    ji, jk = relative_jacobians(x[i], x[k])
    j = np.hstack([ji, jk])
    joint = np.block([[m[i], c[i]], [c[i].T, m[k]]])
    s = (j @ joint @ j.T)[:2, :2]
    ci, si = math.cos(x[i, 2]), math.sin(x[i, 2])
    dx, dy = x[k, 0] - x[i, 0], x[k, 1] - x[i, 1]
    r = np.array([ci * dx + si * dy, -si * dx + ci * dy])
    return float(r @ np.linalg.solve(s, r))


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    gate = -2.0 * math.log(1.0 - confidence)
    out = []
    for i in range(k - int(gap) + 1):
        d2 = d2_of(x, m, c, i, k)
        if math.sqrt(d2) <= gate:
            out.append(i)
    return out
