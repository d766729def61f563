import math

import numpy as np


def nees(x_true, x_hat, P):
    """Normalised estimation error squared eᵀ P⁻¹ e with e = x_true − x_hat."""
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    r = math.remainder(e[2], 2 * math.pi)  # in [-pi, pi]; the interval is (-pi, pi]
    e[2] = math.pi if r == -math.pi else r
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
