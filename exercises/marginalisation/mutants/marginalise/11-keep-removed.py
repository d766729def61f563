# mistake: reads keep as the variables to remove, and returns the system of the others
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    m = [int(k) for k in keep]
    a = [i for i in range(len(H)) if i not in m]
    x = np.linalg.solve(H[np.ix_(m, m)], np.column_stack([H[np.ix_(m, a)], b[m]]))
    return np.column_stack([H[np.ix_(a, a)], b[a]]) - H[np.ix_(a, m)] @ x
