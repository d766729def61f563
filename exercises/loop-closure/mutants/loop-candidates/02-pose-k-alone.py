# mistake: the world offset t_k - t_i gated with the current pose's own marginal covariance
import math

import numpy as np


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    k = len(x) - 1
    gate = -2.0 * math.log(1.0 - confidence)
    s = m[k][:2, :2]
    out = []
    for i in range(k - int(gap) + 1):
        w = x[k, :2] - x[i, :2]
        if float(w @ np.linalg.solve(s, w)) <= gate:
            out.append(i)
    return out
