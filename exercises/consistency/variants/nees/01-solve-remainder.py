# method: numpy solve, heading wrapped with math.remainder
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.asarray(x_true, dtype=float) - np.asarray(x_hat, dtype=float)
    e[2] = math.remainder(e[2], 2 * math.pi)
    if e[2] == -math.pi:  # remainder lands in [-pi, pi]; the interval is (-pi, pi]
        e[2] = math.pi
    return float(e @ np.linalg.solve(np.asarray(P, dtype=float), e))
