import numpy as np
from scipy.linalg import cho_factor, cho_solve


def marginal_covariance(H, block):
    """(H^-1)[block, block] from a Cholesky factor and k solves."""
    H = np.array(H, dtype=float)
    idx = [int(k) for k in block]
    units = np.zeros((len(H), len(idx)))
    for col, k in enumerate(idx):
        units[k, col] = 1.0
    columns = cho_solve(cho_factor(H), units)
    return columns[idx, :]
