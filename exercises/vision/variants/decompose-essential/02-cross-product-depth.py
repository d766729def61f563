# method: depths in closed form from cross products with x2, a plain loop over sign choices
import math

import numpy as np


def decompose_essential(E, x1, x2):
    U, S, Vt = np.linalg.svd(np.array(E, dtype=float))
    if np.linalg.det(U) < 0:
        U[:, 2] *= -1  # negating the null column leaves U diag(s, s, 0) Vt unchanged
    if np.linalg.det(Vt) < 0:
        Vt[2, :] *= -1
    x1 = np.array([float(v) for v in x1])
    x2 = np.array([float(v) for v in x2])
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    for Wk in (W, W.T):
        R = U @ Wk @ Vt
        for sign in (1.0, -1.0):
            t = sign * U[:, 2] / np.linalg.norm(U[:, 2])
            ray = R @ x1
            c = np.cross(x2, ray)
            z1 = -float(np.dot(np.cross(x2, t), c)) / float(np.dot(c, c))
            X2 = z1 * ray + t
            if z1 > 0 and X2[2] > 0 and math.isfinite(z1):
                return np.concatenate([R, t[:, None]], axis=1)
    raise ValueError("no valid candidate")
