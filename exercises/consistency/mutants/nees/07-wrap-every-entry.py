# mistake: every entry of the error wrapped, positions included
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e = np.array([math.remainder(v, 2 * math.pi) for v in e])
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
