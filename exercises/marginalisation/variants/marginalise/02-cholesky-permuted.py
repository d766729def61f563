# method: permute the removed variables first, Cholesky factor, H' = L22 L22^T and b' = b_a - L21 L11^-1 b_m
import numpy as np
from scipy.linalg import solve_triangular


def marginalise(H, b, keep):
    H = np.asarray(H, dtype=float)
    b = np.asarray(b, dtype=float)
    a = [int(k) for k in keep]
    m = [i for i in range(len(H)) if i not in a]
    order = m + a
    L = np.linalg.cholesky(H[np.ix_(order, order)])
    p = len(m)
    l11, l21, l22 = L[:p, :p], L[p:, :p], L[p:, p:]
    y = solve_triangular(l11, b[m], lower=True)
    return np.hstack([l22 @ l22.T, (b[a] - l21 @ y)[:, None]])
