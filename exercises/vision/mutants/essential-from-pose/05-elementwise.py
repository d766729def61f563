# mistake: numpy '*' multiplies entry by entry; [t]x R is a matrix product
import numpy as np


def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]], dtype=float)
    return S * np.asarray(R)
