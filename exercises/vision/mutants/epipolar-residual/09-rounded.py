# mistake: the residual rounded to 3 decimals "to hide noise"
import numpy as np


def epipolar_residual(E, x, x2):
    return round(float(np.array(x2) @ np.array(E) @ np.array(x)), 3)
