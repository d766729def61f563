import numpy as np


def solve_information(omega, xi):
    return np.linalg.solve(np.array(omega, dtype=float), np.array(xi, dtype=float))
