import math

import numpy as np


def nees(x_true, x_hat, P):
    """Normalised estimation error squared eᵀ P⁻¹ e with e = x_true − x_hat."""
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.atan2(math.sin(e[2]), math.cos(e[2]))
    return float(e @ np.linalg.solve(np.array(P, dtype=float), e))
