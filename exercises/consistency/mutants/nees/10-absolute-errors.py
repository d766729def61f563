# mistake: abs() on the errors: cross terms lose their sign
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.remainder(e[2], 2 * math.pi)
    e = np.abs(e)
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
