# mistake: the estimate's heading wrapped, but not the difference
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = x_true[2] - math.remainder(x_hat[2], 2 * math.pi)
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
