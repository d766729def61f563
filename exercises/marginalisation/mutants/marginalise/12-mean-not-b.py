# mistake: returns the kept variables' marginal mean (H^-1 b)_a in place of the information vector b'
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    h_new = H[np.ix_(a, a)] - H[np.ix_(a, m)] @ np.linalg.solve(H[np.ix_(m, m)], H[np.ix_(m, a)])
    mean = np.linalg.solve(H, b)
    return np.column_stack([h_new, mean[a]])
