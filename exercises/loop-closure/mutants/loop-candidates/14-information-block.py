# mistake: the information block (inverse of Sigma_r, top-left 2x2): heading conditioned on
import math

import numpy as np


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    gate = -2.0 * math.log(1.0 - confidence)
    out = []
    for i in range(k - int(gap) + 1):
        ci, si = math.cos(x[i, 2]), math.sin(x[i, 2])
        dx, dy = x[k, 0] - x[i, 0], x[k, 1] - x[i, 1]
        ji = np.array([[-ci, -si, -si * dx + ci * dy], [si, -ci, -ci * dx - si * dy], [0, 0, -1]])
        jk = np.array([[ci, si, 0], [-si, ci, 0], [0, 0, 1]])
        j = np.hstack([ji, jk])
        info = np.linalg.inv(j @ np.block([[m[i], c[i]], [c[i].T, m[k]]]) @ j.T)[:2, :2]
        r = np.array([ci * dx + si * dy, -si * dx + ci * dy])
        if float(r @ info @ r) <= gate:
            out.append(i)
    return out
