# mistake: takes each variance as 1 / H_ii and the cross-covariances as zero
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    return np.diag([1.0 / H[k, k] for k in block])
