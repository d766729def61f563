# mistake: the points are normalised to unit length first; the residual must use [u, v, 1] as given
import numpy as np


def epipolar_residual(E, x, x2):
    a = np.array(x, dtype=float) / np.linalg.norm(x)
    b = np.array(x2, dtype=float) / np.linalg.norm(x2)
    return float(b @ np.array(E) @ a)
