# mistake: Gauss-Jordan inversion in place on np.asarray(H), which is the caller's own array when H is a float ndarray
import numpy as np


def marginal_covariance(H, block):
    A = np.asarray(H, dtype=float)
    n = len(A)
    inv = np.eye(n)
    for v in range(n):
        p = A[v, v]
        A[v, :] /= p
        inv[v, :] /= p
        for i in range(n):
            if i != v:
                f = A[i, v]
                A[i, :] -= f * A[v, :]
                inv[i, :] -= f * inv[v, :]
    a = list(block)
    return inv[np.ix_(a, a)]
