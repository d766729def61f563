# method: explicit inverse, the heading difference as the angle of a complex quotient
import cmath

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = cmath.phase(cmath.exp(1j * x_true[2]) / cmath.exp(1j * x_hat[2]))
    if e[2] == -np.pi:  # phase() may give -pi for a half turn; the interval is (-pi, pi]
        e[2] = np.pi
    return float(e.T @ np.linalg.inv(np.array(P, dtype=float)) @ e)
