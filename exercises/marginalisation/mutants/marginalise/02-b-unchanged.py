# mistake: updates H but forgets the information vector: b' = b_a
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    h_new = H[np.ix_(a, a)] - H[np.ix_(a, m)] @ np.linalg.solve(H[np.ix_(m, m)], H[np.ix_(m, a)])
    return np.column_stack([h_new, b[a]])
