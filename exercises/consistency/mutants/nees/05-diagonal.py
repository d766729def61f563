# mistake: each squared error over its own variance: the correlations of P dropped
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.remainder(e[2], 2 * math.pi)
    return float(np.sum(e**2 / np.diag(np.array(P, dtype=float))))
