# mistake: inverts H_mm entry by entry on its diagonal, as if the removed variables were independent
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    inv = np.diag(1.0 / np.diag(H[np.ix_(m, m)]))
    h_am = H[np.ix_(a, m)]
    return np.column_stack([H[np.ix_(a, a)] - h_am @ inv @ h_am.T, b[a] - h_am @ inv @ b[m]])
