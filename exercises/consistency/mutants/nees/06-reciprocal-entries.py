# mistake: P⁻¹ taken entry by entry (1 / P), infinite where P has zeros
import math

import numpy as np


def nees(x_true, x_hat, P):
    e = np.array(x_true, dtype=float) - np.array(x_hat, dtype=float)
    e[2] = math.remainder(e[2], 2 * math.pi)
    with np.errstate(divide="ignore"):
        inv = 1.0 / np.array(P, dtype=float)
    inv[~np.isfinite(inv)] = 0.0
    return float(e @ inv @ e)
