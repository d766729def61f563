# mistake: the heading error left unwrapped
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
