# mistake: computes the marginal information H_aa - H_am H_mm^-1 H_ma and forgets to invert it
import numpy as np


def marginal_covariance(H, block):
    H = np.array(H, dtype=float)
    a = list(block)
    m = [i for i in range(len(H)) if i not in a]
    if not m:
        return H[np.ix_(a, a)]
    return H[np.ix_(a, a)] - H[np.ix_(a, m)] @ np.linalg.solve(H[np.ix_(m, m)], H[np.ix_(m, a)])
