# method: numpy.linalg.solve on the lists directly
import numpy as np


def solve_information(omega, xi):
    return np.linalg.solve(omega, xi)
