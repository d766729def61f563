# method: order the block last, factor H = L L^T; the block's marginal information is L22 L22^T, so Sigma_aa = L22^-T L22^-1
import numpy as np
from scipy.linalg import solve_triangular


def marginal_covariance(H, block):
    H = np.asarray(H, dtype=float)
    a = [int(k) for k in block]
    m = [i for i in range(len(H)) if i not in a]
    order = m + a
    L = np.linalg.cholesky(H[np.ix_(order, order)])
    l22 = L[len(m):, len(m):]
    inv_l22 = solve_triangular(l22, np.eye(len(a)), lower=True)
    return inv_l22.T @ inv_l22
