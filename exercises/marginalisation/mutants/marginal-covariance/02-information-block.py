# mistake: returns the block of H itself, as if marginalising an information matrix were dropping rows and columns
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    a = list(block)
    return H[np.ix_(a, a)]
