# mistake: inverts the block of H alone, which is the covariance of the block given all other variables
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    a = list(block)
    return np.linalg.inv(H[np.ix_(a, a)])
