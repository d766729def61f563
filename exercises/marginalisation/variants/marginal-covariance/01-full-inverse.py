# method: invert all of H and select the block's rows and columns with np.ix_
import numpy as np


def marginal_covariance(H, block):
    S = np.linalg.inv(np.asarray(H, dtype=float))
    idx = np.asarray(block, dtype=int)
    return S[np.ix_(idx, idx)]
