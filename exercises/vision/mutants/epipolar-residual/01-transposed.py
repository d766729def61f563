# mistake: x^T E x' (the two images swapped)
import numpy as np


def epipolar_residual(E, x, x2):
    return float(np.dot(x, np.dot(E, x2)))
