# mistake: an integer array for the skew matrix truncates fractional translations
import numpy as np


def essential_matrix(t, R):
    S = np.zeros((3, 3), dtype=int)
    S[0, 1], S[0, 2] = -t[2], t[1]
    S[1, 0], S[1, 2] = t[2], -t[0]
    S[2, 0], S[2, 1] = -t[1], t[0]
    return S @ np.asarray(R)
