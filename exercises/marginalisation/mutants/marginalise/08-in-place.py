# mistake: eliminates in place on np.asarray(H), which is the caller's own array when H is a float ndarray
import numpy as np


def marginalise(H, b, keep):
    A = np.asarray(H, dtype=float)
    g = np.asarray(b, dtype=float)
    keep = [int(k) for k in keep]
    n = len(A)
    alive = list(range(n))
    for v in range(n):
        if v in keep:
            continue
        alive.remove(v)
        for i in alive:
            f = A[i, v] / A[v, v]
            A[i, :] -= f * A[v, :]
            g[i] -= f * g[v]
    return np.column_stack([A[np.ix_(keep, keep)], g[keep]])
