# mistake: adds the correction terms instead of subtracting them
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    m = [i for i in range(len(H)) if i not in a]
    x = np.linalg.solve(H[np.ix_(m, m)], np.column_stack([H[np.ix_(m, a)], b[m]]))
    return np.column_stack([H[np.ix_(a, a)], b[a]]) + H[np.ix_(a, m)] @ x
