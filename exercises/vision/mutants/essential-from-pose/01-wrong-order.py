# mistake: R [t]x instead of [t]x R (matrix products do not commute)
import numpy as np


def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]], dtype=float)
    return np.asarray(R) @ S
