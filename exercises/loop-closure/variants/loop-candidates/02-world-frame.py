# method: in world coordinates: w = t_k - t_i, the heading of pose i swinging it by (w_y, -w_x)
import math

import numpy as np


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.array(poses, dtype=float)
    m = np.array(marginals, dtype=float)
    c = np.array(cross, dtype=float)
    k = len(x) - 1
    gate = -2.0 * math.log1p(-confidence)
    out = []
    for i in range(0, k - int(gap) + 1):
        w = x[k, :2] - x[i, :2]
        # R_i r = w: a change of pose i's heading turns r's image in the world by (w_y, -w_x)
        jw = np.zeros((2, 6))
        jw[:, 0:2] = -np.eye(2)
        jw[:, 2] = [w[1], -w[0]]
        jw[:, 3:5] = np.eye(2)
        joint = np.zeros((6, 6))
        joint[:3, :3], joint[:3, 3:], joint[3:, :3], joint[3:, 3:] = m[i], c[i], c[i].T, m[k]
        s = jw @ joint @ jw.T
        if float(w @ np.linalg.inv(s) @ w) <= gate:
            out.append(i)
    return out
