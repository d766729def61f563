# mistake: a half-precision array to "save memory": 10000.01 is stored as 10000
import numpy as np


def build_omega(n, edges):
    omega = np.zeros((n, n), dtype=np.float16)
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
    return omega.astype(float)
