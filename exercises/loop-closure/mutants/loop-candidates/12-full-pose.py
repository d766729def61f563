# mistake: the whole relative pose, heading included, gated with chi-square of 3 dof
import math

import numpy as np
from scipy.stats import chi2


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    gate = chi2.ppf(confidence, 3)
    out = []
    for i in range(k - int(gap) + 1):
        ci, si = math.cos(x[i, 2]), math.sin(x[i, 2])
        dx, dy = x[k, 0] - x[i, 0], x[k, 1] - x[i, 1]
        ji = np.array([[-ci, -si, -si * dx + ci * dy], [si, -ci, -ci * dx - si * dy], [0, 0, -1]])
        jk = np.array([[ci, si, 0], [-si, ci, 0], [0, 0, 1]])
        j = np.hstack([ji, jk])
        s = j @ np.block([[m[i], c[i]], [c[i].T, m[k]]]) @ j.T
        r = np.array([ci * dx + si * dy, -si * dx + ci * dy, wrap(x[k, 2] - x[i, 2])])
        if float(r @ np.linalg.solve(s, r)) <= gate:
            out.append(i)
    return out
