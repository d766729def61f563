# mistake: multiplies by H_mm where its inverse belongs
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    h_am, h_mm = H[np.ix_(a, m)], H[np.ix_(m, m)]
    return np.column_stack([H[np.ix_(a, a)] - h_am @ h_mm @ h_am.T, b[a] - h_am @ h_mm @ b[m]])
