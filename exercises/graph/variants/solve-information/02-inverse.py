# method: the explicit inverse times xi, returned as a list
import numpy as np


def solve_information(omega, xi):
    return list(np.linalg.inv(np.array(omega, dtype=float)) @ np.array(xi, dtype=float))
