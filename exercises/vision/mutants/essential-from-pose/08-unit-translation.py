# mistake: t normalised to unit length ("E is only defined up to scale"): wrong scale, and NaN when t = 0
import numpy as np


def essential_matrix(t, R):
    tx, ty, tz = np.asarray(t, dtype=float) / np.linalg.norm(t)
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]])
    return S @ np.asarray(R)
