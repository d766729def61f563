# mistake: one entry of the skew matrix has the wrong sign (+t_y in the bottom-left corner)
import numpy as np


def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [ty, tx, 0]], dtype=float)
    return S @ np.asarray(R)
