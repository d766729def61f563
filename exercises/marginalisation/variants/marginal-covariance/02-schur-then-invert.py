# method: marginalise every other variable with the Schur complement, then invert the small information matrix
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    a = [int(k) for k in block]
    m = [i for i in range(len(H)) if i not in a]
    h = H[np.ix_(a, a)]
    if m:
        h = h - H[np.ix_(a, m)] @ np.linalg.solve(H[np.ix_(m, m)], H[np.ix_(m, a)])
    return np.linalg.inv(h).tolist()
