# method: the formula with an explicit inverse of H_mm, index lists built with numpy's setdiff1d
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=np.float64)
    b = np.array(b, dtype=np.float64).ravel()
    a = np.asarray(keep, dtype=int)
    m = np.setdiff1d(np.arange(H.shape[0]), a)
    inv = np.linalg.inv(H[np.ix_(m, m)])
    h_new = H[np.ix_(a, a)] - H[np.ix_(a, m)] @ inv @ H[np.ix_(m, a)]
    b_new = b[a] - H[np.ix_(a, m)] @ inv @ b[m]
    return np.column_stack((h_new, b_new)).tolist()
