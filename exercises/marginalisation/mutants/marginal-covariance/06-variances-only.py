# mistake: returns only the marginal variances, on a diagonal, dropping the cross-covariances
import numpy as np


def marginal_covariance(H, block):
    S = np.linalg.inv(np.array(H, dtype=float))
    return np.diag([S[k, k] for k in block])
