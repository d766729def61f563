# mistake: computes the error in place in np.asarray(x_true, dtype=float), which is the caller's own array when x_true is one
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.asarray(x_true, dtype=float)
    e -= np.asarray(x_hat, dtype=float)
    r = math.remainder(e[2], 2 * math.pi)
    e[2] = math.pi if r == -math.pi else r
    return float(e @ np.linalg.solve(np.asarray(P, dtype=float), e))
