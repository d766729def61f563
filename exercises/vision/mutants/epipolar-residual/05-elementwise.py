# mistake: numpy '*' broadcasts instead of multiplying matrices: sum of E_ik x'_k x_k
import numpy as np


def epipolar_residual(E, x, x2):
    return float(np.sum(np.array(x2) * np.array(E) * np.array(x)))
