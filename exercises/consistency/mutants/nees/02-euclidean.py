# mistake: eᵀe: the squared error, P ignored
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.remainder(e[2], 2 * math.pi)
    return float(e @ e)
