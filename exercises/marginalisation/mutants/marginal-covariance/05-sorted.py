# mistake: sorts the block, so rows and columns come out in increasing index order instead of block's order
import numpy as np


def marginal_covariance(H, block):
    S = np.linalg.inv(np.array(H, dtype=float))
    a = sorted(int(k) for k in block)
    return S[np.ix_(a, a)]
