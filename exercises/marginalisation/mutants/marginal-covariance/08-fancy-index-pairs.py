# mistake: indexes the inverse as S[block, block], which pairs the two lists entry by entry (a vector of variances)
import numpy as np


def marginal_covariance(H, block):
    S = np.linalg.inv(np.array(H, dtype=float))
    block = list(block)
    return S[block, block]
