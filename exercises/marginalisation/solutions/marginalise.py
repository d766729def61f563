import numpy as np


def marginalise(H, b, keep):
    """[H' | b'] after marginalising every variable not in keep out of (H, b)."""
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = [int(k) for k in keep]
    m = [i for i in range(len(H)) if i not in a]
    h_aa, h_am, h_mm = H[np.ix_(a, a)], H[np.ix_(a, m)], H[np.ix_(m, m)]
    x = np.linalg.solve(h_mm, np.column_stack([h_am.T, b[m]]))
    return np.column_stack([h_aa, b[a]]) - h_am @ x
