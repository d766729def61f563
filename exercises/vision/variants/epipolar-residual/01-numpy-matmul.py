# method: numpy matrix products x2 @ E @ x
import numpy as np


def epipolar_residual(E, x, x2):
    return float(np.array(x2) @ np.array(E) @ np.array(x))
