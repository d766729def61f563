# mistake: the heading error wrapped into [0, 2π) instead of (−π, π]
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = e[2] % (2 * math.pi)
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
