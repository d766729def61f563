# mistake: marginalises as in covariance form: just drops the other variables' rows and columns
import numpy as np


def marginalise(H, b, keep):
    H = np.array(H, dtype=float)
    b = np.array(b, dtype=float)
    a = list(keep)
    return np.column_stack([H[np.ix_(a, a)], b[a]])
