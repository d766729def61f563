# mistake: abs() of the residual, as if it were a distance; the sign is part of x'^T E x
import numpy as np


def epipolar_residual(E, x, x2):
    return abs(float(np.array(x2) @ np.array(E) @ np.array(x)))
