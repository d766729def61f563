# mistake: adds the correction in the Schur complement before inverting it
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    a = list(block)
    m = [i for i in range(len(H)) if i not in a]
    h = H[np.ix_(a, a)]
    if m:
        h = h + H[np.ix_(a, m)] @ np.linalg.solve(H[np.ix_(m, m)], H[np.ix_(m, a)])
    return np.linalg.inv(h)
