# mistake: wraps the heading error with atan2(sin, cos), which leaves an error of exactly -pi at -pi instead of pi (the sign matters when the heading is correlated with the position)
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.atan2(math.sin(e[2]), math.cos(e[2]))
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
