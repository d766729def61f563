# mistake: assumes the kept variables are the first len(keep) ones, and slices H there
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    k = len(keep)
    x = np.linalg.solve(H[k:, k:], np.column_stack([H[k:, :k], b[k:]]))
    return np.column_stack([H[:k, :k], b[:k]]) - H[:k, k:] @ x
