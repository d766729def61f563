# method: Cholesky whitening, NEES = |L⁻¹ e|², heading wrapped with a while loop
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    while e[2] > math.pi:
        e[2] -= 2 * math.pi
    while e[2] <= -math.pi:
        e[2] += 2 * math.pi
    w = np.linalg.solve(np.linalg.cholesky(np.array(P, dtype=float)), e)
    return float(w @ w)
