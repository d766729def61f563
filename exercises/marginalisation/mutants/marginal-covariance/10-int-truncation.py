# mistake: Gauss-Jordan on np.array(H) without a dtype, so whole-number inputs are truncated to ints
import numpy as np


def marginal_covariance(H, block):
    A = np.array(H)
    n = len(A)
    inv = np.eye(n)
    for v in range(n):
        p = A[v, v]
        A[v, :] = A[v, :] / p
        inv[v, :] = inv[v, :] / p
        for i in range(n):
            if i != v:
                f = A[i, v]
                A[i, :] = A[i, :] - f * A[v, :]
                inv[i, :] = inv[i, :] - f * inv[v, :]
    a = list(block)
    return inv[np.ix_(a, a)]
