# mistake: reads H_mm^-1 as the block (H^-1)_mm of the whole inverse, not the inverse of the block H_mm
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    inv_mm = np.linalg.inv(H)[np.ix_(m, m)]
    h_am = H[np.ix_(a, m)]
    return np.column_stack([H[np.ix_(a, a)] - h_am @ inv_mm @ h_am.T, b[a] - h_am @ inv_mm @ b[m]])
