# mistake: eliminates in a copy made with np.array(H) (no dtype), so whole-number inputs are truncated to ints
import numpy as np


def marginalise(H, b, keep):
    A = np.array(H)
    g = np.array(b)
    keep = [int(k) for k in keep]
    n = len(A)
    alive = list(range(n))
    for v in range(n):
        if v in keep:
            continue
        alive.remove(v)
        for i in alive:
            f = A[i, v] / A[v, v]
            A[i, :] = A[i, :] - f * A[v, :]
            g[i] = g[i] - f * g[v]
    return np.column_stack([A[np.ix_(keep, keep)], g[keep]])
