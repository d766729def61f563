# method: a Python loop over the searched poses, the 6x6 joint covariance built with np.block
import math

import numpy as np


def relative_jacobians(xi, xk):
    """J_i and J_k of r = x_i^-1 (+) x_k at the given poses."""
    c, s = math.cos(xi[2]), math.sin(xi[2])
    dx, dy = xk[0] - xi[0], xk[1] - xi[1]
    ji = np.array([[-c, -s, -s * dx + c * dy], [s, -c, -c * dx - s * dy], [0.0, 0.0, -1.0]])
    jk = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return ji, jk


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    gate = -2.0 * math.log(1.0 - confidence)  # the chi-square quantile with 2 dof
    out = []
    for i in range(k - int(gap) + 1):
        ji, jk = relative_jacobians(x[i], x[k])
        j = np.hstack([ji, jk])
        joint = np.block([[m[i], c[i]], [c[i].T, m[k]]])
        s = (j @ joint @ j.T)[:2, :2]
        ci, si = math.cos(x[i, 2]), math.sin(x[i, 2])
        dx, dy = x[k, 0] - x[i, 0], x[k, 1] - x[i, 1]
        r = np.array([ci * dx + si * dy, -si * dx + ci * dy])
        if float(r @ np.linalg.solve(s, r)) <= gate:
            out.append(i)
    return out
